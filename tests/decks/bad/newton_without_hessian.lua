local sim = slender.simulation { dimension = 2, quiet = true }
sim:wire { name = "w", nodes = 5 }
sim:bond("spring", { k = 10 })
sim:bond("bend2d/hysteresis", { k = 1, yield_curvature = 0.5 })
sim:integrator("verlet", { dt = 0.01 })
-- Newton needs every style's Hessian: the message names the one without and the way out
sim:minimize { method = "newton" }

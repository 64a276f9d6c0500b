local sim = slender.simulation { dimension = 2, quiet = true }
sim:wire { name = "w", nodes = 10 }
sim:bond("spring", { k = 100 })
sim:bond("bend2d", { k = 1 })
sim:integrator("verlet", { dt = 0.01 })
sim:thermo { every = 10, columns = { "step", "energy.bending" } }
sim:run(20)

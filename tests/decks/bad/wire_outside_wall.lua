-- A wire that starts outside its wall: refused before the first step, naming the node.
local sim = slender.simulation { dimension = 2, quiet = true }
sim:wire { name = "w", nodes = 10, spacing = 1.0 }
sim:bond("spring", { k = 100 })
sim:fix("cavity", "wall/circle", { radius = 5, diameter = 1.0, stiffness = 100 })
sim:integrator("verlet", { dt = 0.01 })
sim:run(10)

local sim = slender.simulation { dimension = 2 }
sim:wire { name = "w", nodes = 10 }
sim:bond("spring", { k = 100 })
sim:integrator("verlet", {})
sim:read_checkpoint("no_such_checkpoint.h5")

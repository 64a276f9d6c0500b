local sim = slender.simulation { dimension = 2 }
sim:wire { name = "w", nodes = 10 }
sim:integrator("gear", { values = 9 })

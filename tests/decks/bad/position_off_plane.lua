local sim = slender.simulation { dimension = 2, quiet = true }
sim:wire { name = "w", nodes = 10 }
sim:set_position(3, { 1, 2, 0.5 })

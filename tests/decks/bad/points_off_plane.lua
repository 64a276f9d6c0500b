local sim = slender.simulation { dimension = 2, quiet = true }
sim:wire { name = "w", points = { { 0, 0 }, { 1, 0, 0 }, { 2, 0, 0.3 } } }

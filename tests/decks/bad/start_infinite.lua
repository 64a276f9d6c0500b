local sim = slender.simulation { dimension = 2, quiet = true }
sim:wire { name = "w", nodes = 4, start = { math.huge, 0 } }

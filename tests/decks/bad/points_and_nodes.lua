local sim = slender.simulation { dimension = 2, quiet = true }
-- nodes would be ignored: the points alone place the wire
sim:wire { name = "w", nodes = 50, points = { { 0, 0 }, { 1, 0 }, { 2, 0 } } }

local sim = slender.simulation { dimension = 2, quiet = true }
-- a tilted direction would have been normalised in 3D and then lost its z: a shorter wire
sim:wire { name = "w", nodes = 10, direction = { 1, 0, 1 } }

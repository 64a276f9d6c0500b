local sim = slender.simulation { dimension = 2, quiet = true }
sim:wire { name = "ring", nodes = 8, radius = 1 }
-- a closed chain has no end for a moment
sim:fix("turn", "moment2d", { chain = "ring", moment = 1 })

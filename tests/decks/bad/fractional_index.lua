local sim = slender.simulation { dimension = 2, quiet = true }
sim:wire { name = "w", nodes = 20 }
local x = sim:position(10.5)

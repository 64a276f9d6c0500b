-- a ring whose inner radius is not inside its outer one: the message names the deck's keys
local sim = slender.simulation { dimension = 3 }
sim:mesh { name = "s", shape = "ring", inner_radius = 2, radius = 1, edge = 0.3 }

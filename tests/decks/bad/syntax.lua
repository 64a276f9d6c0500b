-- a deck with a Lua syntax error on line 3
local sim = slender.simulation { dimension = 2 }
sim:wire { name = "w", nodes = 10 spacing = 1 }

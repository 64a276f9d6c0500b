local sim = slender.simulation { dimension = 2 }
sim:wire { name = "w", nodes = 10 }
-- helper functions keep the line of the call that failed inside them
local function load(g) sim:fix("load", "force/constant", { group = g, force = { 0, 1 } }) end
load("tip")

-- Test deck of the Python package: a style table with a key the spring does not declare;
-- the engine must stop before the first step, naming this file and line.
local slender = require("slender")
local sim = slender.simulation { dimension = 2 }
sim:wire { name = "w", nodes = 3 }
sim:bond("spring", { k = 1, stiffnes = 2 })

-- Test deck of the Python package: an open wire clamped at its root and loaded at its tip,
-- and a closed ring, both elastic, integrated for a fixed number of steps with a frame every
-- `every` steps. Prints where nodes ended up (RESULT) so that the tests can compare the dump.
local slender = require("slender")
local steps = slender.var("steps", 200)
local every = slender.var("every", 50)
local sim = slender.simulation { dimension = 2, seed = 3 }
sim:wire { name = "arm", nodes = 12, spacing = 1.0, start = { -6, 0 }, direction = { 1, 0 }, perturb = 0.05 }
sim:wire { name = "ring", nodes = 10, radius = 3.0, start = { 0, 8 }, perturb = 0.05 }
sim:bond("spring", { k = 1000 })
sim:bond("bend2d", { k = 60 })
sim:group("root", { chain = "arm", nodes = { 1 } })
sim:group("tip", { chain = "arm", nodes = { -1 } })
sim:fix("clamp", "clamp", { group = "root", rotation = true })
sim:fix("load", "force/constant", { group = "tip", force = { 0, -0.5 } })
sim:integrator("verlet", { dt = 0.01 })
sim:dump("traj", "h5md", { file = "chains2d.h5", every = every, fields = { "position", "velocity" } })
sim:run(steps)
local checkpoint = slender.var("checkpoint", "")
if checkpoint ~= "" then sim:write_checkpoint(checkpoint) end
local tip = sim:chain_node("arm", 12)
local tip_x, tip_y = sim:position(tip)
local ring_x, ring_y = sim:position(sim:chain_node("ring", 4))
slender.result { case = "chains2d", label = "two chains", steps = sim:step(), nodes = sim:nnodes(),
                 tip = tip, tip_x = tip_x, tip_y = tip_y }
slender.result { ring_x = ring_x, ring_y = ring_y }

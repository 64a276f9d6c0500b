-- Test deck of the Python package: a simply supported square plate under a uniform load,
-- damped explicit dynamics for a fixed number of steps, the limit surface dumped every
-- `every` steps with its bending energy density per face.
local slender = require("slender")
local steps = slender.var("steps", 60)
local every = slender.var("every", 20)
local a, n = 1.0, 4
local sim = slender.simulation { dimension = 3, quiet = true }
local nodes, tris = sim:mesh { name = "plate", shape = "rectangle", size = { a, a }, edge = a / n }
sim:shell("koiter", { mesh = "plate", thickness = 0.05, young = 1e4, poisson = 0.3,
                      boundary = "simply_supported", load = { 0, 0, 1.0 } })
sim:integrator("newmark", { damping = 5 })
sim:dump("surface", "shell", { file = "plate.h5", every = every, mesh = "plate", faces = { "koiter.Ub" } })
sim:run(steps)
slender.result { nodes = nodes, triangles = tris, steps = sim:step(), energy_bend = sim:value("energy.bend") }

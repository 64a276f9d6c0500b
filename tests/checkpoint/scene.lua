-- A small crumpling scene (injection, node-edge contact with friction, wall with
-- friction) for the checkpoint tests: -v mode=write runs it and writes a checkpoint,
-- -v mode=read reads one into the same scene and runs on (-v out=FILE: and writes one).
-- -v checkpoint_every=N adds periodic checkpoints (periodic.h5).
local mode = slender.var("mode", "write")
local file = slender.var("file", "scene.h5")
local sim = slender.simulation { dimension = 2, seed = 3, quiet = true }
local r = 4.0
sim:wire { name = "w", nodes = 12, spacing = 1.0, start = { -r - 11.5, 0 }, direction = { 1, 0 } }
sim:bond("spring", { k = 1000 })
sim:bond("bend2d/hysteresis", { k = 10, yield_curvature = 0.3 })
sim:pair("contact/node-edge", { stiffness = 1e3, mu_static = 0.3, mu_dynamic = 0.25 })
sim:fix("cavity", "wall/circle", { radius = r, diameter = 1.0, stiffness = 1e3, mu_static = 0.3,
                                   mu_dynamic = 0.25, openings = { math.pi } })
sim:fix("drag", "damping/viscous", { gamma = 0.5 })
sim:fix("feed", "inject/wire", { chain = "w", radius = r, channels = "left", speed = slender.var("speed", 0.5),
                                 perturb = 0.05 })
sim:integrator("verlet", { dt = 0.005 })
-- -v checkpoint_every=N: periodic checkpoints to periodic.h5 (the kill test)
local every = slender.var("checkpoint_every", 0)
if every > 0 then sim:dump("periodic", "checkpoint", { file = "periodic.h5", every = every }) end
if mode == "read" then sim:read_checkpoint(file) end
sim:run(slender.var("steps", 12000))
if mode == "write" then sim:write_checkpoint(file) end
local out = slender.var("out", "")
if out ~= "" then sim:write_checkpoint(out) end
slender.result { nodes = sim:value("nodes"), contacts = sim:value("contact/node-edge.contacts") }

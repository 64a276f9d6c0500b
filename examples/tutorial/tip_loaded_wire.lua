-- Purpose: the README tutorial: a 2D wire clamped at one end, loaded at the tip,
-- relaxed by damped Gear dynamics until the largest force is below 1e-6.
-- Expected run time: under a second.
local N = slender.var("nodes", 21)          -- -v nodes=41 on the command line overrides it
local sim = slender.simulation { dimension = 2, seed = 7 }
-- a straight chain of N nodes, one length unit apart, along x
sim:wire { name = "w", nodes = N, spacing = 1.0, start = { 0, 0 }, direction = { 1, 0 }, mass = 1 }
sim:bond("spring", { k = 1000 })            -- stretching, k1 = YA / l0
sim:bond("bend2d", { k = 60 })              -- bending, moment k2 * turning angle
sim:group("root", { chain = "w", nodes = { 1 } })
sim:group("tip", { chain = "w", nodes = { -1 } })   -- 1-based; negative counts from the end
sim:fix("clamp", "clamp", { group = "root", rotation = true })   -- also fixes the first edge
sim:fix("load", "force/constant", { group = "tip", force = { 0, -0.05 } })
sim:fix("drag", "damping/viscous", { gamma = 0.15 })
-- dt = "auto": safety x the stable step of the stiffest term (printed when the run starts)
sim:integrator("gear", { values = 5, dt = "auto", safety = 0.5 })
sim:thermo { every = 5000, columns = { "step", "time", "ke", "energy.bend", "fmax" }, file = "thermo.csv" }
-- an H5MD trajectory, and wire.h5.xdmf next to it for ParaView
sim:dump("traj", "h5md", { file = "wire.h5", every = 5000, fields = { "position", "velocity" } })
sim:run { steps = 400000, every = 1000, callback = function(s)
  return s:value("fmax") < 1e-6       -- return true to stop early
end }
local x, y = sim:position(-1)
print("tip at", x, y)

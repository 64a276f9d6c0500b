-- Benchmark deck: slender's side of the LAMMPS peer comparison (scripts/bench_peer_wire2d.sh).
-- The peer's scene (../shared/peers/in.wire2d.lmp): a bead chain from the same data
-- file (spiral start), stretching k = 1000, bending 60, frictional contact (mu = 0.3),
-- a harmonic circular wall and viscous damping 0.1, velocity Verlet, dt = 0.02.
-- Ours uses its own models for the same physics: node-edge contact with the quadratic
-- law of MODELS.md §2.3 instead of bead-bead Hertz, chain neighbours excluded.
--   slender bench_wire2d.lua -v data=w2d_N10000.data -v R=100 -v nwarm=500 -v nrun=5000
local data = slender.var("data")
local R = slender.var("R", 100)
local dt = slender.var("dt", 0.02)
local nwarm = slender.var("nwarm", 500)
local nrun = slender.var("nrun", 2000)
assert(data, "give -v data=<LAMMPS data file>")

-- read the "Atoms" section: id type x y z ... (ids in chain order)
local atoms, in_atoms = {}, false
for line in io.lines(data) do
  if line:match("^%s*Atoms") then in_atoms = true
  elseif in_atoms and line:match("^%s*%a") then break
  elseif in_atoms then
    local id, _, x, y = line:match("^%s*(%d+)%s+(%d+)%s+(%S+)%s+(%S+)")
    if id then atoms[tonumber(id)] = { tonumber(x), tonumber(y) } end
  end
end
local pts = {}
for i = 1, #atoms do pts[i] = atoms[i] end
assert(#pts > 1, "no atoms read from " .. data)

local sim = slender.simulation { dimension = 2, quiet = true }
sim:wire { name = "w", points = pts }
sim:bond("spring", { k = 1000 })
sim:bond("bend2d", { k = 60 })
sim:pair("contact/node-edge", { diameter = 1, stiffness = 1e4, damping = 20, mu_static = 0.3,
                                stick_stiffness = 2000, skin = 0.3 })
sim:fix("cavity", "wall/circle", { radius = R, diameter = 1, stiffness = 500, exponent = 1 })
sim:fix("drag", "damping/viscous", { gamma = 0.1 })
sim:integrator("verlet", { dt = dt })
sim:run(nwarm)
local t0 = slender.clock()
sim:run(nrun)
local wall = slender.clock() - t0
slender.result { code = "slender", nodes = #pts, steps = nrun, loop_s = wall,
  node_steps_per_s = #pts * nrun / wall, contacts = sim:value("contact/node-edge.contacts"),
  builds = sim:value("contact/node-edge.builds") }

-- Benchmark deck: slender's side of the 3D LAMMPS peer comparison (scripts/bench_peer.sh
-- --dim 3). The peer's scene (../shared/peers/in.wire3d.lmp): a bead chain from the same
-- data file (self-avoiding random walk), stretching k = 1000, bending 60, frictional
-- contact (mu = 0.3), a harmonic spherical wall and viscous damping 0.1, velocity Verlet,
-- dt = 0.02. Ours uses its own models for the same physics: a discrete elastic rod
-- (rod/straight, YI = 60 stores the peer's 30 theta^2 per hinge) and segment-segment
-- contact of radius 0.5 with the linear law of MODELS.md §5.1 instead of bead-bead
-- Hertz, chain neighbours excluded.
--   slender -t 1 bench_wire3d.lua -v data=w3d_N10000.data -v R=40 -v nwarm=500 -v nrun=2000
local data = slender.var("data")
local R = slender.var("R", 40)
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
    local id, _, x, y, z = line:match("^%s*(%d+)%s+(%d+)%s+(%S+)%s+(%S+)%s+(%S+)")
    if id then atoms[tonumber(id)] = { tonumber(x), tonumber(y), tonumber(z) } end
  end
end
local pts = {}
for i = 1, #atoms do pts[i] = atoms[i] end
assert(#pts > 1, "no atoms read from " .. data)

local sim = slender.simulation { dimension = 3, quiet = true }
sim:wire { name = "w", points = pts }
sim:bond("spring", { k = 1000 })
sim:bond("rod/straight", { YI = 60 })
sim:pair("contact/segment", { radius = 0.5, stiffness = 1000, damping = 20, mu_static = 0.3,
                              stick_stiffness = 500, skin = 0.3 })
sim:fix("cavity", "wall/sphere", { radius = R, diameter = 1, stiffness = 500, exponent = 1 })
sim:fix("drag", "damping/viscous", { gamma = 0.1 })
sim:integrator("verlet", { dt = dt })
sim:run(nwarm)
local t0 = slender.clock()
sim:run(nrun)
local wall = slender.clock() - t0
slender.result { code = "slender", nodes = #pts, steps = nrun, loop_s = wall,
  node_steps_per_s = #pts * nrun / wall, contacts = sim:value("contact/segment.contacts"),
  builds = sim:value("contact/segment.builds") }

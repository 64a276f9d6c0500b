-- Benchmark deck: slender's side of the LAMMPS peer comparison (scripts/bench_peer.sh).
-- The peers' scenes (../shared/peers/in.wire2d.lmp, in.wire3d.lmp): a bead chain from the
-- same data file (2D spiral, 3D self-avoiding random walk), stretching k = 1000, bending 60,
-- frictional contact (mu = 0.3), a harmonic circular (2D) or spherical (3D) wall and viscous
-- damping 0.1, velocity Verlet, dt = 0.02. Ours uses its own models for the same physics:
-- 2D node-edge contact with the quadratic law of docs/models.md §2.3, 3D a discrete elastic rod
-- (rod/straight, YI = 60 stores the peer's 30 theta^2 per hinge) with segment-segment
-- contact of radius 0.5 and the linear law of §5.1, instead of bead-bead Hertz; chain
-- neighbours excluded.
--   slender -t 1 bench_wire.lua -v dim=2 -v data=w2d_N10000.data -v R=100 -v nwarm=500 -v nrun=5000
--   slender -t 1 bench_wire.lua -v dim=3 -v data=w3d_N10000.data -v R=40 -v nwarm=500 -v nrun=3000
local dim = slender.var("dim", 2)
local data = slender.var("data")
local R = slender.var("R", dim == 2 and 100 or 40)
local dt = slender.var("dt", 0.02)
local nwarm = slender.var("nwarm", 500)
local nrun = slender.var("nrun", 2000)
assert(data, "give -v data=<LAMMPS data file>")
assert(dim == 2 or dim == 3, "dim must be 2 or 3")

-- read the "Atoms" section: id type x y z ... (ids in chain order)
local atoms, in_atoms = {}, false
for line in io.lines(data) do
  if line:match("^%s*Atoms") then in_atoms = true
  elseif in_atoms and line:match("^%s*%a") then break
  elseif in_atoms then
    local id, _, x, y, z = line:match("^%s*(%d+)%s+(%d+)%s+(%S+)%s+(%S+)%s+(%S+)")
    if id then atoms[tonumber(id)] = dim == 2 and { tonumber(x), tonumber(y) }
                                     or { tonumber(x), tonumber(y), tonumber(z) } end
  end
end
local pts = {}
for i = 1, #atoms do pts[i] = atoms[i] end
assert(#pts > 1, "no atoms read from " .. data)

local sim = slender.simulation { dimension = dim, quiet = true }
sim:wire { name = "w", points = pts }
sim:bond("spring", { k = 1000 })
local pair
if dim == 2 then
  sim:bond("bend2d", { k = 60 })
  pair = "contact/node-edge"
  sim:pair(pair, { diameter = 1, stiffness = 1e4, damping = 20, mu_static = 0.3,
                   stick_stiffness = 2000, skin = 0.3 })
  sim:fix("cavity", "wall/circle", { radius = R, diameter = 1, stiffness = 500, exponent = 1 })
else
  sim:bond("rod/straight", { YI = 60 })
  pair = "contact/segment"
  sim:pair(pair, { radius = 0.5, stiffness = 1000, damping = 20, mu_static = 0.3,
                   stick_stiffness = 500, skin = 0.3 })
  sim:fix("cavity", "wall/sphere", { radius = R, diameter = 1, stiffness = 500, exponent = 1 })
end
sim:fix("drag", "damping/viscous", { gamma = 0.1 })
sim:integrator("verlet", { dt = dt })
sim:run(nwarm)
local t0 = slender.clock()
sim:run(nrun)
local wall = slender.clock() - t0
slender.result { code = "slender", nodes = #pts, steps = nrun, loop_s = wall,
  node_steps_per_s = #pts * nrun / wall, contacts = sim:value(pair .. ".contacts"),
  builds = sim:value(pair .. ".builds") }

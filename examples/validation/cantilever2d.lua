-- Purpose: clamped 2D wire under a tip load; tip position against the elastica
-- (any load) and Euler-Bernoulli P L^3 / (3 EI) (small loads). -v model=rod3d runs
-- the same beam as a 3D discrete elastic rod (bond rod/straight), which must
-- converge to the same reference.
-- Expected run time: about 1 s with the defaults (41 nodes, gear5).
--
-- Units: EI = 1, L = 1, mass per length 1. EA = 1e5 EI / L^2 (a wire of diameter
-- ~0.013 L). The reference is the extensible elastica with the same EA, solved in
-- lib/elastica.lua by shooting; scripts/elastica.py cross-checks its inextensible limit.
--   slender cantilever2d.lua -v nodes=81 -v integrator=verlet -v alpha=3
-- -v integrator=newton solves the statics directly (Newton with exact Hessians,
-- docs/models.md §9.3): about ten iterations instead of 10^4-10^5 steps.
local ref = require("lib.elastica")

local N = slender.var("nodes", 41)              -- nodes from the clamp to the tip
local integ = slender.var("integrator", "gear5") -- verlet | gear4 | gear5 | gear6 | fire | newton
local alpha = slender.var("alpha", 0.01)        -- load P L^2 / EI
local dt = slender.var("dt", "auto")
local write_output = slender.var("output", false)
-- bend2d | rod3d (3D discrete elastic rod, rod/straight) | cosserat (3D quaternion rod)
local model = slender.var("model", "bend2d")
assert(model == "bend2d" or model == "rod3d" or model == "cosserat",
       "model must be bend2d, rod3d or cosserat")
local dim = model == "bend2d" and 2 or 3
local function vec(x, y) return dim == 3 and { x, y, 0 } or { x, y } end

local L, EI, EA = 1.0, 1.0, 1e5
-- Staggered clamp: the hinge at the clamped node stands for the wire over half a
-- segment on each side, so the clamp edge runs from -h/2 to h/2 and the beam's
-- bending length is exactly L (a clamp at the node itself would add h/2: O(h) error).
local h = L / (N - 0.5)
local P = alpha * EI / L ^ 2

local sim = slender.simulation { dimension = dim, seed = 1 }
-- N + 1 nodes: the clamped pair at -h/2 and h/2, then the free nodes up to the tip at L
sim:wire { name = "beam", nodes = N + 1, spacing = h, start = vec(-h / 2, 0), direction = vec(1, 0), mass = h }
sim:bond("spring", { k = EA / h })  -- k1 = EA / l0 (docs/models.md §1)
if model == "rod3d" then
  sim:bond("rod/straight", { YI = EI })  -- docs/models.md §3
elseif model == "cosserat" then
  -- docs/models.md §4 with C = coupling_factor EA; a light, critically damped frame
  -- (rotational inertia is not part of a static reference). The coupling penalty lets
  -- the tangent leave d3 like a shear compliance: an error floor that falls as 1/C
  -- (alpha = 3, 41 nodes: 8.9e-4 at C = EA, 1.4e-4 at 10 EA; dt and cost go as sqrt(C))
  local C = slender.var("coupling_factor", 1) * EA
  local Ir = 1e-3 * h * h
  local kq = 4 * EA * h  -- the frame's damping stays tuned to C = EA (tuned to C it stalls)
  sim:bond("rod/cosserat", { YI = EI, GJ = EI / 1.33, coupling = C, rot_inertia = Ir,
                             rot_damping = 2 * math.sqrt(kq * 4 * Ir * h) })
else
  sim:bond("bend2d", { k = EI / h })  -- k2 = EI / l0
end
sim:group("base", { chain = "beam", nodes = { 1, 2 } })
sim:group("tip", { chain = "beam", nodes = { -1 } })
sim:fix("clamp", "clamp", { group = "base" })
sim:fix("load", "force/constant", { group = "tip", force = vec(0, -P) })
-- near-critical damping of the first bending mode (omega_1 = 3.516 sqrt(EI / (rho A L^4)))
if integ ~= "fire" and integ ~= "newton" then sim:fix("drag", "damping/viscous", { gamma = 2 * 3.516 * h }) end
ref.integrator(sim, integ, dt)
if write_output then
  sim:thermo { every = 2000, columns = { "step", "time", "ke", "energy.stretch", "energy.bend", "fmax" },
               file = "cantilever2d_thermo.csv" }
  sim:dump("traj", "h5md", { file = "cantilever2d.h5", every = 2000, fields = { "position", "force" } })
end

local t0 = slender.clock()
-- the floor sits above the round-off of the stiff axial springs (k1 eps L ~ 1e-9)
local tol = math.max(1e-7 * P, 5e-9)
local steps = ref.relax(sim, integ, tol, 5e7, 1e-15 * P ^ 2 * L ^ 3 / EI)
local wall = slender.clock() - t0

local x, y = sim:position(-1)
local xr, yr = ref.cantilever_tip(P, EI, EA, L)
local eb = -P * L ^ 3 / (3 * EI)
local rel = math.sqrt((x - xr) ^ 2 + (y - yr) ^ 2) / math.abs(yr)
slender.result { case = "cantilever2d", model = model, alpha = alpha, nodes = N, integrator = integ, dt = sim:dt(),
  steps = steps, wall_s = wall, tip_x = x, tip_y = y, ref_x = xr, ref_y = yr, rel_error = rel,
  eb_y = eb, eb_error = math.abs(y - eb) / math.abs(eb),
  node_steps_per_s = (N + 1) * steps / math.max(wall, 1e-9) }
-- tests pass -v check=TOL to turn the comparison into an assertion
local check = slender.var("check")
if check then
  assert(rel < check, string.format("relative error %.3e exceeds the tolerance %.3e", rel, check))
end

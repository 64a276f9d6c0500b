-- Purpose: Michell's instability of a twisted elastic ring (docs/models.md §4.5, §7.1 A-2):
-- a closed, naturally straight rod bent into a circle and twisted by a total angle
-- Theta stays planar below Theta_c = 2 pi sqrt(3) YI / GJ and buckles out of plane
-- above it. Found by bisection over runs of the quaternion Cosserat rod (damped
-- Gear dynamics from a small out-of-plane perturbation).
-- Expected run time: ~1 min with the defaults (24 nodes, gear q = 6).
--
-- Reference: J. H. Michell (1889/90), "On the stability of a bent and twisted
-- wire", Messenger of Mathematics 19, 181-184; derived e.g. in Goriely, "Twisting
-- and buckling: a short history of Michell's instability" (J. Elasticity 84, 2006):
-- a closed ring of bending stiffness B = YI and twist stiffness C = GJ with total
-- twist Tw is stable for Tw < 2 pi sqrt(3) B / C. (docs/models.md §4.5 notes that the thesis
-- prints the ratio upside down.) The twist is imposed as a rest twist kbar3 =
-- -Theta / L on untwisted frames, which loads the ring with the same uniform
-- twisting moment GJ Theta / L as twisting its frames by Theta.
--   slender michell.lua -v nodes=48 -v GJ=0.75
local fast = slender.var("fast", 0) == 1   -- the example suite: 12 nodes, 6 bisections
local N = slender.var("nodes", fast and 12 or 24)
local YI = slender.var("YI", 1.0)
local GJ = slender.var("GJ", 1.0 / 1.33)   -- a circular section with nu = 0.33: GJ = YI / (1 + nu)
local iterations = slender.var("iterations", fast and 6 or 10)
local R0 = 1.0
local L = 2 * math.pi * R0
local h = 2 * R0 * math.sin(math.pi / N)
local theta_ref = 2 * math.pi * math.sqrt(3) * YI / GJ

-- -v criterion=static: relax the planar ring and test the sign of the lowest eigenvalue
-- of its stiffness matrix (sim:lowest_stiffness), the exact threshold of the discrete
-- ring; rigid motions and a common roll of the frames are free (zero) modes
local criterion = slender.var("criterion", "dynamic")
assert(criterion == "dynamic" or criterion == "static", "criterion must be dynamic or static")

-- true if the ring leaves its plane under total twist theta
local function buckles(theta)
  local sim = slender.simulation { dimension = 3, seed = 7, quiet = true }
  local pts = {}
  for i = 0, N - 1 do
    local phi = 2 * math.pi * i / N
    -- a small out-of-plane perturbation of mode 2 (Michell's mode) and mode 3
    local z = criterion == "static" and 0 or 1e-3 * R0 * (math.sin(2 * phi) + 0.5 * math.cos(3 * phi))
    pts[#pts + 1] = { R0 * math.cos(phi), R0 * math.sin(phi), z }
  end
  sim:wire { name = "ring", points = pts, closed = true, mass = h }
  local YA = 1e4 * YI / R0 ^ 2   -- nearly inextensible
  sim:bond("spring", { k = YA / h })
  sim:bond("rod/cosserat", { YI = YI, GJ = GJ, coupling = YA, rot_inertia = 0.05 * h,
                             rest_curvature = { 0, 0, -theta / L }, rot_damping = 0.05 * h })
  sim:fix("drag", "damping/viscous", { gamma = 0.5 * h })
  sim:integrator("gear", { values = 6, dt = "auto" })
  if criterion == "static" then
    sim:minimize { ftol = 1e-10, max_steps = 200000 }
    local lowest = sim:lowest_stiffness { eps = 1e-7 * R0 }
    -- the free modes sit at zero within about 1e-7 (the stiff springs); the buckling
    -- mode falls by about 0.05 YI / R0^3 per radian of twist near the threshold
    return lowest < -1e-5 * YI / R0 ^ 3, sim:step()
  end
  local function amplitude()
    local a = 0
    for i = 1, N do
      local _, _, z = sim:position(i)
      a = math.max(a, math.abs(z))
    end
    return a
  end
  -- Above the threshold the perturbation grows until the ring writhes (and, with no
  -- self-contact here, may pass through itself and come back flat with less twist),
  -- so a trial buckles when the out-of-plane amplitude ever reaches 10 times its
  -- start, or when it is still growing at the end of the run.
  local a0 = amplitude()
  local T = slender.var("time", 60.0)
  local chunk = math.floor(0.05 * T / sim:suggest_dt(0.5))
  local a_half
  for k = 1, 20 do
    sim:run(chunk)
    local a = amplitude()
    if a > 10 * a0 then return true, sim:step() end
    if k == 10 then a_half = a end
  end
  return amplitude() > a_half, sim:step()
end

local t0 = slender.clock()
local lo, hi, steps = 0.5 * theta_ref, 1.5 * theta_ref, 0
assert(not buckles(lo), "the ring buckles at half the Michell twist")
assert(buckles(hi), "the ring stays planar at 1.5 times the Michell twist")
for _ = 1, iterations do
  local mid = 0.5 * (lo + hi)
  local b, n = buckles(mid)
  steps = steps + n
  if b then hi = mid else lo = mid end
end
local wall = slender.clock() - t0
local theta_c = 0.5 * (lo + hi)
local rel = math.abs(theta_c - theta_ref) / theta_ref
slender.result { case = "michell", nodes = N, YI = YI, GJ = GJ, theta_c = theta_c, ref = theta_ref,
  rel_error = rel, bracket = (hi - lo) / theta_ref, runs = iterations + 2, steps = steps, wall_s = wall }
local check = slender.var("check")
if check then
  assert(rel < check, string.format("relative error %.3e exceeds the tolerance %.3e", rel, check))
end

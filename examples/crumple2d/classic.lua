-- Purpose: the thesis' classic crumpling scene (W2-1, MODELS.md §7.2): an elasto-
-- plastic wire pushed from two opposite channels into a circular cavity until it
-- jams; loop cascades near the wall with two-fold symmetry.
-- Expected run time: f = 10 (fast mode, -v f=10): ~10 s; f = 100: hours.
--
-- Parameters: d = l0 = 1, k1 = 1000, k2 = 60, m = 1 (MODELS.md §1); yield curvature
-- 0.04, mu_st = 5, and the thesis' s = 0.08 read as the injection speed (d per time
-- unit, reading (a) of §2.6) with K_h = 0.05 K_e. Defaults marked [C] in §2.3:
-- k_c = 10 k1 / d, d_c = 0.1 * 2 sqrt(m k_c d), k_st = k1 / d, v_th = 1e-3 v_in,
-- mu_d = 0.9 mu_st; jamming when the averaged injection force exceeds 0.1 k1 l0.
local f = slender.var("f", 100)                 -- cavity radius over wire diameter
local s = slender.var("s", 0.08)                -- the thesis' s, read as the feed speed
local yield = slender.var("yield", 0.04)        -- kappa_theta
local mu = slender.var("mu", 5.0)               -- mu_st
local hardening = slender.var("hardening", 0.05) -- K_h / K_e
local seed = slender.var("seed", 1)
local max_phi = slender.var("max_phi", 1.0)
local output = slender.var("output", true)

local d, k1, k2, m = 1.0, 1000.0, 60.0, 1.0
local r = f * d
local kc = 10 * k1 / d

local sim = slender.simulation { dimension = 2, seed = seed }
-- a straight wire along the diameter, three nodes into each channel
local n = 2 * math.floor(r) + 7
sim:wire { name = "wire", nodes = n, spacing = d, start = { -(n - 1) / 2 * d, 0 }, mass = m, perturb = 0.01 * d }
sim:bond("spring", { k = k1 })
sim:bond("bend2d/hysteresis", { k = k2, yield_curvature = yield, hardening_ratio = hardening })
sim:pair("contact/node-edge", { diameter = d, stiffness = kc, damping = 0.1 * 2 * math.sqrt(m * kc * d),
  mu_static = mu, mu_dynamic = 0.9 * mu, stick_stiffness = k1 / d, slip_velocity = 1e-3 * s, skin = d })
sim:fix("cavity", "wall/circle", { radius = r, diameter = d, stiffness = kc,
  damping = 0.1 * 2 * math.sqrt(m * kc * d), mu_static = mu, mu_dynamic = 0.9 * mu,
  stick_stiffness = k1 / d, slip_velocity = 1e-3 * s })  -- channel nodes are kinematic: no wall
sim:fix("drag", "damping/viscous", { gamma = 0.01 * math.sqrt(k1 * m) })
sim:fix("feed", "inject/wire", { chain = "wire", radius = r, speed = s, diameter = d,
  jam_force = 0.1 * k1 * d, jam_window = 1000, max_phi = max_phi })
-- dt = 0.02 sqrt(m / k1) (MODELS.md §2.5 [C]): 2.8x below the nominal "auto" step,
-- which assumes one contact of overlap d/10 per node; dense packings load a node
-- with several deeper contacts and Gear q = 5 is stable only for omega dt < 0.42
sim:integrator("gear", { values = 5, dt = slender.var("dt", 0.02 * math.sqrt(m / k1)) })
sim:compute("count", "count", {})
sim:thermo { every = 20000, file = "classic_thermo.csv",
  columns = { "step", "time", "feed.phi", "feed.force_avg", "contact/node-edge.contacts",
              "cavity.contacts", "energy.bend", "ke", "count.nodes" } }
if output then
  sim:dump("traj", "h5md", { file = "classic.h5", every = 50000, fields = { "position", "bend.plastic_curvature" } })
end

local t0 = slender.clock()
sim:run { steps = slender.var("max_steps", 1e9) }
local wall = slender.clock() - t0
slender.result { case = "crumple2d/classic", f = f, seed = seed, phi = sim:value("feed.phi"),
  jammed = sim:value("feed.jammed"), steps = sim:step(), wall_s = wall, nodes = sim:nnodes(),
  ke_per_node = sim:value("ke") / sim:nnodes(), force = sim:value("feed.force_avg"),
  contacts = sim:value("contact/node-edge.contacts"),
  node_steps_per_s = sim:nnodes() * sim:step() / math.max(wall, 1e-9) }
-- tests: -v check=true asserts that the run ended quasi-statically (a jam, not a burst)
if slender.var("check", false) then
  assert(sim:value("ke") / sim:nnodes() < 0.1, "the run ended with kinetic energy " .. sim:value("ke"))
end

-- The 3D packing scene of docs/models.md §5 (thesis ch. 4): a rod fed through a nozzle
-- at (0, 0, R) into a rigid sphere of radius R until the injection force passes a
-- threshold. Shared by the decks in this folder, which pick the rod model.
--
-- Units (§1): rod radius a = 1, Y = 1000, nu = 0.33, density 1, rest segment length
-- l0 = a. So YA = pi Y, YI = pi Y / 4, node mass rho A l0 = pi. Defaults marked [C]
-- in §5: contact and wall stiffness E* of two rest edges, k_st = E* / 10, contact
-- damping 0.1 * 2 sqrt(m E*), feed speed 1e-3 sqrt(Y / rho), viscous damping
-- 0.01 sqrt(k1 m), adaptive velocity Verlet. Stop when the injection force averaged over jam_time
-- (1000 steps of the reference dt) exceeds F_stop = max(0.01 YA, 20 YI / R^2): the [C] default 0.01 YA alone
-- (F R^2 / YI = 0.04 R^2) lies below the Euler load that the first head-on contact
-- of the straight rod with the far wall needs (measured: 10 YI / R^2 is not enough at
-- R = 5, where the rod, clamped in the nozzle and held by friction, hits head-on) for R < 16,
-- and would end every small-sphere run there. Nodes leaving the nozzle get a random
-- transverse displacement of 0.01 a (-v perturb=): a perfectly straight feed hits the
-- far wall exactly head-on and overshoots the Euler load (R = 10 stopped at phi = 0.015).
local M = {}
local here = debug.getinfo(1, "S").source:match("^@(.*)/[^/]*$") or "."
local snapshot = dofile(here .. "/../../lib/snapshot.lua")

function M.build(p)
  -- -v fast=1 (the example suite and the tests): R = 4 a unless given
  local R = slender.var("R", slender.var("fast", 0) == 1 and 4 or p.R)
  local seed = slender.var("seed", 1)
  local mu_s = slender.var("mu_s", 0.2)
  local mu_d = slender.var("mu_d", 0.18)
  local output = slender.var("output", true)
  local name = p.name

  local a, Y, nu, rho = 1.0, 1000.0, 0.33, 1.0
  local l0 = a
  local A, I = math.pi * a ^ 2, math.pi * a ^ 4 / 4
  local YA, YI = Y * A, Y * I
  local m = rho * A * l0
  local estar = 2 * math.pi * Y * (2 * l0) / (8 * (1 - nu ^ 2))
  local dc = 0.1 * 2 * math.sqrt(m * estar)
  local speed = slender.var("speed", 1e-3 * math.sqrt(Y / rho))

  local sim = slender.simulation { dimension = 3, seed = seed }
  -- a straight rod on the nozzle axis: three nodes in the nozzle, two inside;
  -- random transverse displacements of 0.01 a break the symmetry (§5.3 [T])
  sim:wire { name = "rod", nodes = 6, spacing = l0, start = { 0, 0, R + 3 * l0 },
             direction = { 0, 0, -1 }, mass = m, perturb = 0.01 * a }
  sim:bond("spring", { k = YA / l0 })             -- stretching (4.7)
  -- the rod model; it keeps per-node bending energies (bend.energy) for the dumps
  p.bend(sim, { YI = YI, YA = YA, l0 = l0, m = m })
  sim:pair("contact/segment", { radius = a, youngs_modulus = Y, poisson = nu, damping = dc,
                                mu_static = mu_s, mu_dynamic = mu_d,
                                -- rebuilt once a node moved skin/2, so results do not depend
                                -- on it; 0.2 a ran low torsion at R = 20 (1500 contacts) about
                                -- 9 % faster than 0.5 a, with the same result in every digit
                                skin = slender.var("skin", 0.2 * a) })
  sim:fix("sphere", "wall/sphere", { radius = R, diameter = 2 * a, stiffness = estar, exponent = 1,
                                     damping = dc, mu_static = mu_s, mu_dynamic = mu_d,
                                     stick_stiffness = 0.1 * estar })
  -- -v damping=viscous (default): drag 0.01 sqrt(k1 m) on absolute velocities, which
  -- also resists the rod sliding along itself (gamma v per moving node). -v
  -- damping=internal: bond damper on the relative velocity of neighbours instead. At
  -- R = 10 the injection force agrees within 0.1 in F R^2 / YI up to phi = 0.2: the packed
  -- rod is mostly at rest, so the drag is a small part of the force. -v drag= scales either.
  local damping = slender.var("damping", "viscous")
  if damping == "internal" then
    sim:bond("damper", { gamma = slender.var("drag", 0.1) * math.sqrt(YA / l0 * m) })
  elseif damping == "viscous" then
    sim:fix("drag", "damping/viscous", { gamma = slender.var("drag", 0.01) * math.sqrt(YA / l0 * m) })
  else
    error("damping must be viscous or internal, got " .. tostring(damping))
  end
  sim:fix("feed", "inject/wire", { chain = "rod", radius = R, center = { 0, 0, 0 }, channels = "nozzle",
    direction = { 0, 0, -1 }, speed = speed, diameter = 2 * a, rotation = p.rotation or "free",
    perturb = slender.var("perturb", 0.01 * a),
    jam_force = slender.var("stop_force", math.max(0.01 * YA, 20 * YI / R ^ 2)),
    -- the force is averaged over jam_time: 1000 steps of the "auto" step these decks ran
    -- at until 2026-12 (a time, so that the stop means the same at any dt)
    jam_time = slender.var("jam_time", p.jam_time),
    max_phi = slender.var("max_phi", 1.0),
    -- -v jam_min_phi=: no stop below this density. The straight rod first crosses the
    -- sphere at phi = 1.5 (a/R)^2; at R = 20 that head-on hit passes F_stop = 39 (the
    -- run stopped at phi = 0.004), so R = 20 runs use 3 (a/R)^2
    jam_min_phi = slender.var("jam_min_phi", 0.0) })
  -- -v integrator=verlet | gear | gear4 | gear5 | gear6 (gear: q = 6) | ...
  -- Adaptive velocity Verlet at 0.7 of its stable step: 4.9x (low torsion) and 5.7x (high
  -- torsion) fewer steps than Gear q = 6 at its "auto" step, with phi_max, E_b and the
  -- contacts within the seed scatter at R = 6 (4 seeds, docs/performance.md); at 0.85 two
  -- of four low-torsion runs jam early, at 1.2 (fixed) every run blows up (-v safety=)
  local integrator = slender.var("integrator", "verlet")
  local q = integrator:match("^gear(%d?)$")
  if q then
    sim:integrator("gear", { values = tonumber(q) or 6, dt = slender.var("dt", "auto") })
  elseif integrator == "verlet" then
    -- -v trust_measured=true: the contacts' measured stiffness alone (also below its
    -- nominal estimate) sets their share of the step (docs/performance.md)
    sim:integrator("verlet", { dt = slender.var("dt", "auto"), safety = slender.var("safety", 0.7),
                               adaptive = slender.var("adaptive", true),
                               trust_measured = slender.var("trust_measured", false) })
  else
    sim:integrator(integrator, { dt = slender.var("dt", "auto") })
  end
  sim:compute("count", "count", {})
  sim:compute("gyr", "gyration", { group = "rod", inside = R })
  local restart = slender.var("restart", "")
  local columns = { "step", "time", "feed.phi", "feed.force_avg", "contact/segment.contacts",
                    "sphere.contacts", "energy.bend", "energy.stretch", "energy.contact", "energy.twist",
                    "gyr.rg", "ke", "count.nodes" }
  -- rods with frames: the largest |t - d3| of the step (docs/models.md §4.3 wants < 1e-2),
  -- so the coupling constant can be judged over the whole run, not only at its end
  if pcall(sim.value, sim, "rod/cosserat.misalignment") then
    columns[#columns + 1] = "rod/cosserat.misalignment"
  end
  -- output cadences in time, so that they mean the same rod at any step: a thermo line per
  -- half a radius fed, a frame per 4 a (-v thermo_every= / dump_every= take steps instead)
  local function cadence(steps_var, length)
    local n = slender.var(steps_var, 0)
    if n > 0 then return { every = n } end
    return { interval = length / speed }
  end
  local th = cadence("thermo_every", slender.var("thermo_length", 0.5 * a))
  th.file, th.append, th.columns = name .. "_thermo.csv", restart ~= "", columns
  sim:thermo(th)
  local traj
  if output then
    -- a restarted run writes a new trajectory file rather than replacing the first
    traj = restart == "" and name .. ".h5" or string.format("%s_%d.h5", name, os.time())
    local dp = cadence("dump_every", slender.var("dump_length", 4 * a))
    dp.file, dp.fields = traj, { "position", "bend.energy" }
    sim:dump("traj", "h5md", dp)
  end
  -- long runs (R >= 20 takes hours to days): -v checkpoint_every=N writes
  -- <name>_restart.h5 every N steps; -v restart=<file> continues from it (thermo CSV
  -- appended, max_steps counted from step 0)
  local checkpoint_every = slender.var("checkpoint_every", 0)
  if checkpoint_every > 0 then
    sim:dump("restart", "checkpoint", { file = name .. "_restart.h5", every = checkpoint_every })
  end
  if restart ~= "" then sim:read_checkpoint(restart) end
  return sim, { name = name, R = R, YI = YI, seed = seed, mu_s = mu_s, speed = speed, traj = traj }
end

function M.run(p)
  local sim, ctx = M.build(p)
  local t0 = slender.clock()
  local node_steps, every = 0, 1000
  sim:run { steps = slender.var("max_steps", 1e9) - sim:step(), every = every,
            callback = function(s) node_steps = node_steps + every * s:nnodes() end }
  local wall = slender.clock() - t0
  local R, YI = ctx.R, ctx.YI
  slender.result { case = "pack3d/" .. ctx.name, R = R, seed = ctx.seed, mu_s = ctx.mu_s,
    speed = ctx.speed, phi = sim:value("feed.phi"), stopped = sim:value("feed.jammed"),
    force_R2_over_YI = sim:value("feed.force_avg") * R * R / YI,
    bend_R_over_YI = sim:value("energy.bend") * R / YI,
    twist_R_over_YI = sim:value("energy.twist") * R / YI,
    -- a large stretch/bend ratio flags a rod compressed by the feed, not packed
    stretch_over_bend = sim:value("energy.stretch") / math.max(sim:value("energy.bend"), 1e-300),
    rg_over_R = sim:value("gyr.rg") / R,
    contacts = sim:value("contact/segment.contacts"), nodes = sim:nnodes(), steps = sim:step(),
    wall_s = wall, node_steps_per_s = node_steps / math.max(wall, 1e-9),
    ke_per_node = sim:value("ke") / sim:nnodes(),
    -- rods with frames: the largest |t - d3| (docs/models.md §4.3 wants < 1e-2)
    misalignment = (pcall(sim.value, sim, "rod/cosserat.misalignment")) and
                   sim:value("rod/cosserat.misalignment") or 0 }
  -- the last frame as a picture, coloured by bending energy
  if ctx.traj then snapshot.render(ctx.traj, ctx.name .. ".png", { radius = R, field = "bend.energy" }) end
  return sim
end

return M

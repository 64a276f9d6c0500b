-- The 2D crumpling scene of docs/models.md §2 (thesis ch. 3): an elasto-plastic wire
-- pushed from two opposite channels into a circular cavity until it jams.
-- Shared by classic.lua, spiral.lua and plastic.lua, which set the parameters.
--
-- Fixed: d = l0 = 1, k1 = 1000, k2 = 60, m = 1 (§1). Defaults marked [C] in §2.3:
-- k_c = 10 k1 / d, d_c = 0.1 * 2 sqrt(m k_c d), k_st = k1 / d, v_th = 1e-3 v_in,
-- mu_d = 0.9 mu_st; a drag 1e-5 sqrt(k1 m) on translations (the thesis' "small viscous
-- damping" read as small enough that the results no longer depend on it,
-- docs/crumple2d/causes.md) and 0.01 sqrt(k2 m) l0 on the turning rate (§2.1); jamming when the
-- injection force averaged over 1000 reference steps (a time) exceeds 0.1 k1 l0 (§2.4);
-- adaptive velocity Verlet (see below). The thesis' s is read as the feed speed (§2.6 (a)).
local M = {}
local here = debug.getinfo(1, "S").source:match("^@(.*)/[^/]*$") or "."
local snapshot = dofile(here .. "/../../lib/snapshot.lua")

-- Builds the scene; returns the simulation and what the report needs.
function M.build(p)
  -- -v fast=1 (the example suite and the tests): f = 10 up to phi = 0.3 (or the deck's
  -- fast_max_phi) unless given
  local fast = slender.var("fast", 0) == 1
  local f = slender.var("f", fast and 10 or p.f)
  local s = slender.var("s", p.s)
  local yield = slender.var("yield", p.yield)
  local mu = slender.var("mu", p.mu)
  -- wire–wall friction; the thesis gives one mu_st for both (§2.3), so it defaults to mu
  local wall_mu = slender.var("wall_mu", mu)
  local hardening = slender.var("hardening", p.hardening or 0.05)
  local seed = slender.var("seed", 1)
  local max_phi = slender.var("max_phi", fast and (p.fast_max_phi or 0.3) or (p.max_phi or 1.0))
  local output = slender.var("output", true)
  local name = p.name

  local d, k1, k2, m = 1.0, 1000.0, 60.0, 1.0
  local r = f * d
  -- -v new_contacts=by_speed: a new contact sticks only when slower than v_th, as the thesis'
  -- text reads (§2.3); the default "stick" starts every new contact stuck
  local new_contacts = slender.var("new_contacts", "stick")
  local kc = 10 * k1 / d
  local dc = 0.1 * 2 * math.sqrt(m * kc * d)

  local sim = slender.simulation { dimension = 2, seed = seed }
  -- a straight wire along the diameter, three nodes into each channel; random
  -- normal displacements of 0.01 d break the symmetry (§2.4)
  local n = 2 * math.floor(r) + 7
  sim:wire { name = "wire", nodes = n, spacing = d, start = { -(n - 1) / 2 * d, 0 }, mass = m,
             perturb = 0.01 * d }
  sim:bond("spring", { k = k1 })
  -- bending dashpot gamma_r = 0.01 sqrt(k2 m) l0 (§2.1 [C])
  local bend = { k = k2, yield_curvature = yield, hardening_ratio = hardening,
                 damping = 0.01 * math.sqrt(k2 * m) * d }
  -- -v transition_ratio= sets delta / kappa_y (the style's default 0.5 when not given; §2.2 [?])
  local transition_ratio = slender.var("transition_ratio", -1)
  if transition_ratio >= 0 then bend.transition = transition_ratio * yield end
  -- -v saturate=true: the literal reading of Alg. 1, a moment that stops growing with plastic flow
  if slender.var("saturate", false) then bend.saturate = true end
  sim:bond("bend2d/hysteresis", bend)
  sim:pair("contact/node-edge", { diameter = d, stiffness = kc, damping = dc, mu_static = mu,
    mu_dynamic = 0.9 * mu, stick_stiffness = k1 / d, slip_velocity = 1e-3 * s, new_contacts = new_contacts,
    -- pair-list skin: the list is rebuilt once a node has moved skin/2, so the results do
    -- not depend on it (f = 10 to its jam: the same in every digit for 0.1 ... 1 d); 0.3 d
    -- took 27 % less CPU than 1 d there
    skin = slender.var("skin", 0.3 * d) })
  -- channel nodes are kinematic, so the wall needs no openings
  sim:fix("cavity", "wall/circle", { radius = r, diameter = d, stiffness = kc, damping = dc,
    mu_static = wall_mu, mu_dynamic = 0.9 * wall_mu, stick_stiffness = k1 / d,
    slip_velocity = 1e-3 * s, new_contacts = new_contacts })
  -- translational damping on absolute velocities, gamma_t = drag_factor * 0.01 sqrt(k1 m)
  -- (§2.1 [C]). The thesis asks for "small viscous damping for stability"; read literally,
  -- small enough that the results no longer depend on it: the 2D causes study
  -- (docs/crumple2d/causes.md) found phi_jam, loops and contacts converged at a factor of
  -- 0.001 at f = 25 and 50 (the same as 0.01 and 1e-4 within the seed scatter), while the
  -- factor 1 these decks used until 2026-12-07 over-damps the wire's slow bending modes
  -- (5x at f = 25, 80x at f = 100) and folds it along the feed axis; -v drag_factor=1 runs
  -- that drag. -v damping=relative puts gamma_t (factor 1 by default) on the relative
  -- velocity of neighbours (bond damper) instead, the other converged reading.
  local damping = slender.var("damping", "absolute")
  local gamma_t = slender.var("drag_factor", damping == "absolute" and 0.001 or 1.0) * 0.01 * math.sqrt(k1 * m)
  if damping == "absolute" then
    sim:fix("drag", "damping/viscous", { gamma = gamma_t })
  elseif damping == "relative" then
    sim:bond("damper", { gamma = gamma_t })
  else
    error("-v damping= must be absolute or relative, got '" .. tostring(damping) .. "'", 0)
  end
  -- the channels are kinematic, so jam_force stands for the feed rollers' strength: 0.1 k1 d
  -- is 10 % axial strain of the wire (docs/crumple2d/timings.md: doubling it moves the
  -- jamming density by 0.006-0.02 at f = 10-50)
  sim:fix("feed", "inject/wire", { chain = "wire", radius = r, speed = s, diameter = d,
    jam_force = slender.var("jam_force", 0.1 * k1 * d),
    -- averaged over 1000 steps of the reference dt 0.01 sqrt(m / k1) (docs/models.md §2.4), as a
    -- time: a step count would average over 10x more wire at 10x the step
    jam_time = slender.var("jam_time", 10 * math.sqrt(m / k1)), max_phi = max_phi })
  -- Velocity Verlet at 0.7 of its stable step ("auto" with safety 0.7, 38x the Gear q = 5
  -- step 0.01 sqrt(m / k1) these decks ran before), lowered before each step when the
  -- contacts as they are (several per node, deep overlaps) are stiffer than the nominal
  -- estimate. The jamming density, A/B, loops, contacts and D agree with the old step and
  -- with safety 0.5 within the seed scatter (docs/performance.md); Gear q = 5 at 10x its
  -- old step loses 15 % of the contacts. -v integrator=gear runs the old step;
  -- -v adaptive=false a fixed one; -v safety=0.5 the more cautious step.
  -- -v integrator=verlet | gear | gear4 | gear5 | gear6 (gear: q = 5) | ...
  local integrator = slender.var("integrator", "verlet")
  local q = integrator:match("^gear(%d?)$")
  if q then
    sim:integrator("gear", { values = tonumber(q) or 5, dt = slender.var("dt", 0.01 * math.sqrt(m / k1)) })
  elseif integrator == "verlet" then
    -- -v trust_measured=true: the contacts' measured stiffness alone (also below its
    -- nominal estimate) sets their share of the step (docs/performance.md)
    sim:integrator("verlet", { dt = slender.var("dt", "auto"), safety = slender.var("safety", 0.7),
                               adaptive = slender.var("adaptive", true),
                               trust_measured = slender.var("trust_measured", false) })
  else
    sim:integrator(integrator, { dt = slender.var("dt", "auto") })
  end
  -- an edge strained beyond max_strain stops the run as a torn wire
  sim:guard { max_strain = slender.var("max_strain", 0.5) }
  sim:compute("count", "count", {})
  sim:compute("shape", "morphology2d", { radius = r })
  sim:compute("loops", "loops2d", { radius = r, diameter = d })
  -- sandbox radii from 2 d to 0.3 r, centres on the wire within 0.7 r of the centre
  -- (small cavities, f < 7, have no room for a sandbox range and go without)
  local with_fractal = 0.3 * r > 2 * d
  if with_fractal then
    sim:compute("frac", "fractal2d", { radius = r, diameter = d, rho_max = 0.3 })
  end
  local restart = slender.var("restart", "")
  local columns = { "step", "time", "feed.phi", "feed.force_avg", "contact/node-edge.contacts",
                    "cavity.contacts", "loops.loops", "loops.holes", "energy.bend",
                    "bend2d/hysteresis.dissipated", "shape.ratio", "shape.winding",
                    "shape.net_winding", "ke", "count.nodes" }
  if with_fractal then table.insert(columns, 9, "frac.D") end
  -- output cadences in time, so that they mean the same wire at any step: a thermo line per
  -- half a diameter fed per channel up to f = 25 and per f/50 diameters beyond (classic to
  -- the jam: ~1 900 lines at f = 50, ~2 900 at f = 100; a line per half diameter, 11 600
  -- lines at f = 100, cost 10 % of that run, the loops and the fractal dimension of 12 000
  -- nodes taking 25 ms a line, docs/performance.md), a frame per 2 d (-v thermo_length= sets
  -- the length, -v thermo_every= / dump_every= take steps instead)
  local function cadence(steps_var, length)
    local n = slender.var(steps_var, 0)
    if n > 0 then return { every = n } end
    return { interval = length / s }
  end
  local th = cadence("thermo_every", slender.var("thermo_length", 0.5 * d * math.max(1, f / 25)))
  th.file, th.append, th.columns = name .. "_thermo.csv", restart ~= "", columns
  sim:thermo(th)
  local traj
  if output then
    -- a restarted run writes a new trajectory file rather than replacing the first
    traj = restart == "" and name .. ".h5" or string.format("%s_%d.h5", name, os.time())
    local dp = cadence("dump_every", slender.var("dump_length", 2 * d))
    dp.file, dp.fields = traj, { "position", "bend.plastic_curvature" }
    sim:dump("traj", "h5md", dp)
  end
  -- long runs: -v checkpoint_every=N writes <name>_restart.h5 every N steps;
  -- -v restart=<file> continues from it (thermo CSV appended)
  local checkpoint_every = slender.var("checkpoint_every", 0)
  if checkpoint_every > 0 then
    sim:dump("restart", "checkpoint", { file = name .. "_restart.h5", every = checkpoint_every })
  end
  if restart ~= "" then sim:read_checkpoint(restart) end
  return sim, { name = name, f = f, s = s, yield = yield, mu = mu, seed = seed,
                with_fractal = with_fractal, traj = traj }
end

-- The RESULT line of a run that took `wall` seconds and `node_steps` node-steps.
function M.report(sim, ctx, wall, node_steps)
  slender.result { case = "crumple2d/" .. ctx.name, f = ctx.f, s = ctx.s, yield = ctx.yield,
    mu = ctx.mu, seed = ctx.seed,
    phi = sim:value("feed.phi"), jammed = sim:value("feed.jammed"), force = sim:value("feed.force_avg"),
    steps = sim:step(), wall_s = wall, nodes = sim:nnodes(),
    contacts = sim:value("contact/node-edge.contacts"), wall_contacts = sim:value("cavity.contacts"),
    ab_ratio = sim:value("shape.ratio"),
    loops = sim:value("loops.loops"), fractal_dimension = ctx.with_fractal and sim:value("frac.D") or 0,
    winding = sim:value("shape.winding"), ke_per_node = sim:value("ke") / sim:nnodes(),
    node_steps_per_s = node_steps / math.max(wall, 1e-9), ended = ctx.ended or "stop" }
end

-- Injects until the wire jams (or max_phi / max_steps) and reports.
function M.run(p)
  local sim, ctx = M.build(p)
  local t0 = slender.clock()
  -- node-steps summed as the wire grows (the node count changes every few hundred steps)
  local node_steps, every = 0, 1000
  local ok, err = pcall(sim.run, sim, { steps = slender.var("max_steps", 1e9) - sim:step(), every = every,
            callback = function(s) node_steps = node_steps + every * s:nnodes() end })
  -- a run the instability guard stopped (typically a frictionless wire overpacked
  -- to phi ~ 0.95 tearing an edge) still reports the last good state, marked
  -- ended=instability, and then fails with the guard's message (exit code 3); a run
  -- stopped by SIGINT/SIGTERM reports where it was, ended=interrupted (exit code 130)
  ctx.ended = ok and "stop" or (slender.interrupted() and "interrupted" or "instability")
  M.report(sim, ctx, slender.clock() - t0, node_steps)
  if not ok then error(err, 0) end
  -- the last frame as a picture, coloured by plastic curvature
  if ctx.traj then
    snapshot.render(ctx.traj, ctx.name .. ".png", { radius = ctx.f, field = "bend.plastic_curvature" })
  end
  -- tests: -v check=true asserts that the run ended quasi-statically (a jam, not a burst)
  if slender.var("check", false) then
    assert(sim:value("ke") / sim:nnodes() < 0.1, "the run ended with kinetic energy " .. sim:value("ke"))
  end
  return sim
end

return M

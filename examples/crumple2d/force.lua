-- Purpose: injection force against packing density by the thesis' protocol (W2-7,
-- docs/models.md §2.4 and §7.2): at every sampled phi the feed stops, the wire relaxes
-- to rest, and the force on the channel nodes is read; then the feed goes on, up
-- to jamming. Writes force_samples.csv (phi, force, ...); scripts/crumple_stats.py fits
-- F ~ (phi_c - phi)^beta.
-- Expected run time (one core): f = 10 (fast mode, -v fast=1): ~4 s; f = 25: ~1 min; f = 35: ~3 min.
-- (Cavities below f = 10 jam at once: the buckled wire grips the wall, mu_st = 5.)
-- Thesis parameters: f = 25, kappa_theta = 0.08, mu_st = 5, s = 0.05 (feed speed;
-- 0.06 in the thesis' text). Elastic variant: -v yield=4.
local scene = require("lib.scene")
-- -v fast=1: f = 10 to jamming with samples every 0.05
local sim, ctx = scene.build { name = "force", f = 25, yield = 0.08, mu = 5.0, s = 0.05, fast_max_phi = 1.0 }
local dphi = slender.var("dphi", slender.var("fast", 0) == 1 and 0.05 or 0.025)
-- at rest: kinetic energy per node below 1e-8 k1 l0^2 (§2.4 [C])
local ke_tol = slender.var("ke_tol", 1e-8 * 1000.0)
local relax_max = slender.var("relax_steps", 2e6)
local out = io.open(ctx.name .. "_samples.csv", "w")
out:write("phi,force,force_avg,ke_per_node,relaxed,relax_steps,step,contacts\n")
local t0 = slender.clock()
sim:run(1)  -- the feed measures phi from the first step on
local target = sim:value("feed.phi") + dphi
local samples, all_relaxed, first_force, last_force = 0, true, nil, nil
while sim:value("feed.jammed") == 0 and sim:step() < slender.var("max_steps", 1e9) do
  sim:run { steps = 1e9, every = 500, callback = function(s) return s:value("feed.phi") >= target end }
  if sim:value("feed.jammed") ~= 0 then break end
  -- hold the wire and let it come to rest
  sim:modify("feed", { speed = 0 })
  local start = sim:step()
  sim:run { steps = relax_max, every = 500,
            callback = function(s) return s:value("ke") / s:nnodes() < ke_tol end }
  local ke = sim:value("ke") / sim:nnodes()
  out:write(string.format("%.6f,%.6g,%.6g,%.3g,%d,%d,%d,%d\n", sim:value("feed.phi"),
    sim:value("feed.force"), sim:value("feed.force_avg"), ke, ke < ke_tol and 1 or 0,
    sim:step() - start, sim:step(), sim:value("contact/node-edge.contacts")))
  out:flush()
  samples = samples + 1
  all_relaxed = all_relaxed and ke < ke_tol
  first_force = first_force or sim:value("feed.force")
  last_force = sim:value("feed.force")
  if sim:value("feed.jammed") ~= 0 then break end
  sim:modify("feed", { speed = ctx.s })
  repeat target = target + dphi until target > sim:value("feed.phi")
end
out:close()
scene.report(sim, ctx, slender.clock() - t0, 0)
print(string.format("force samples: %d (%s_samples.csv)", samples, ctx.name))
-- tests: -v check=true asserts the protocol held: every sample at rest, the force
-- rising towards the jam, and a clean jam at the end
if slender.var("check", false) then
  assert(samples >= 4, "only " .. samples .. " force samples")
  assert(all_relaxed, "a sample did not come to rest within relax_steps")
  assert(last_force > 2 * first_force, "the force did not rise: " .. first_force .. " -> " .. last_force)
  assert(sim:value("feed.jammed") == 1, "the run did not end jammed")
end

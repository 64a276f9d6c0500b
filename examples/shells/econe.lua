-- E-cone (docs/models.md §7.2 S-1): a free disc grows circumferentially, phi_e ramped from 0 in steps with an
-- L-BFGS relaxation preconditioned by the exact Hessian after each (-v precondition=none: plain L-BFGS;
-- -v minimizer=fire: FIRE; -v minimizer=newton: Newton with exact Hessians; -v minimizer=damped: damped
-- Newmark dynamics to a
-- force and a kinetic-energy tolerance; see lib/econe.lua); records E_b_hat(phi_e), the energies, the number of wings and the first
-- self-contact ("kissing" excess angle, refined by bisection), then the contact-plane angle gamma. Plots
-- econe.png (energies and gamma against phi_e) and shape.png (the final surface coloured by U_b).
-- Run time: -v fast=1 about 4 s (FIRE 15 s); the default (h = 0.02, edge 1/16, phi_e to 12) 89 s on one
-- core, 75-84 s with slender -t 2 (plain L-BFGS, -v precondition=none: 180 s and 115 s; FIRE, -v
-- minimizer=fire: about 25 min of CPU, 34 min measured with two other jobs sharing two cores).
-- Options: -v h=0.02 -v edge=0.0625 -v phi_max=12 -v dphi=0.1 -v out=DIR -v boundary=mirror|combined
--          -v inner=0.25 grows a ring (annulus R_i <= r <= 1, both edges free; S-4) instead of a disc
--          -v mode=3 -v mode_amp=1e-3 starts from z = amp r^2 cos(3 phi) (the n = 3 e-cone of S-5)
--          -v contact=0 leaves self-contact out (the self-intersecting branch S-2 compares with); the
--          kiss is then where the wings' mid-surfaces touch (compute far_distance, column mid_gap)
--          -v resume=1 continues an interrupted ramp from its last recorded phi_e (OUT/ramp.h5 and
--          OUT/ramp_state.lua, rewritten after every increment; a fresh start when there are none)
--          -v stop_at=PHI ends the run after the increment that reaches PHI, keeping that state for
--          -v resume=1 (long ramps split over several sessions)
local slender = require("slender")

local fast = slender.var("fast", 0) == 1
local phi_max = slender.var("phi_max", fast and 5.5 or 12.0)
local dphi = slender.var("dphi", fast and 0.5 or 0.1)
local kiss_bisections = slender.var("kiss_bisections", fast and 4 or 6)
-- L-BFGS preconditioned by the factorised exact Hessian: 84 s on the default mesh against
-- 115 s plain and ~25 min for FIRE, nearer Newton's equilibria (docs/shells/README.md)
local scene = require("lib.econe").build{fast = fast, out = "econe_out", minimizer = "lbfgs",
                                         precondition = "hessian"}
local sim, relax, record, out = scene.sim, scene.relax, scene.record, scene.out
local h, edge, inner, nodes, tris = scene.h, scene.edge, scene.inner, scene.nodes, scene.tris
local kiss, kiss_lo, wings_before = nil, nil, 0
-- the wings kiss when they come into contact (at the contact thickness h); with -v contact=0,
-- when their mid-surfaces touch or cross (compute far_distance reads 0)
local function touching()
  if scene.contact then return scene.cv("far_contacts") > 0 end
  return sim:value("gap.distance") == 0
end
local ebmax, phi_ebmax = -1, 0
local prev_phi, phi = 0, 0
local ckpt = out .. "/before_step.h5"

-- resumable ramp: the state after each recorded increment and the ramp's bookkeeping
local ramp_ckpt, ramp_state = out .. "/ramp.h5", out .. "/ramp_state.lua"
local resumed = slender.var("resume", 0) == 1 and loadfile(ramp_state)
if resumed then
  local r = resumed()
  sim:read_checkpoint(ramp_ckpt)
  phi, kiss, kiss_lo, wings_before = r.phi, r.kiss, r.kiss_lo, r.wings_before
  ebmax, phi_ebmax = r.ebmax, r.phi_ebmax
  scene.steps_total, scene.t0 = r.steps_total, scene.t0 - r.wall
  print(string.format("resumed at phi_e = %.4f from %s", phi, ramp_ckpt))
end
scene.open_log("econe.csv", nil, resumed and true or false)
local function save_ramp()
  sim:write_checkpoint(ramp_ckpt)
  local fmt = function(v) return v and string.format("%.17g", v) or "nil" end
  local f = assert(io.open(ramp_state .. ".tmp", "w"))
  f:write(string.format("return {phi = %s, kiss = %s, kiss_lo = %s, wings_before = %s, ebmax = %s, " ..
                        "phi_ebmax = %s, steps_total = %s, wall = %s}\n", fmt(phi), fmt(kiss),
                        fmt(kiss_lo), fmt(wings_before), fmt(ebmax), fmt(phi_ebmax),
                        fmt(scene.steps_total), fmt(slender.clock() - scene.t0)))
  f:close()
  assert(os.rename(ramp_state .. ".tmp", ramp_state))
end
local stop_at = slender.var("stop_at", math.huge)

while phi < phi_max - 1e-12 do
  prev_phi = phi
  sim:write_checkpoint(ckpt)
  phi = math.min(phi_max, phi + dphi)
  local steps = relax(phi)
  if not kiss and not touching() then wings_before = sim:value("rim.n") end
  if not kiss and touching() then
    -- first contact in (prev_phi, phi]: bisect from the last contact-free state
    local lo, hi = prev_phi, phi
    for _ = 1, kiss_bisections do
      local mid = 0.5 * (lo + hi)
      sim:read_checkpoint(ckpt)
      relax(mid)
      if touching() then
        hi = mid
      else
        lo = mid
        sim:write_checkpoint(ckpt)
      end
    end
    kiss, kiss_lo = hi, lo
    print(string.format("first self-contact (kissing) at phi_e in (%.4f, %.4f]", lo, hi))
    sim:read_checkpoint(ckpt)
    steps = relax(phi)
  end
  record(phi, steps)
  if not kiss and sim:value("koiter.Eb_hat") > ebmax then
    ebmax, phi_ebmax = sim:value("koiter.Eb_hat"), phi
  end
  save_ramp()
  if phi >= stop_at - 1e-12 and phi < phi_max - 1e-12 then break end
end
scene.csv:close()
if phi < phi_max - 1e-12 then
  print(string.format("stopped at phi_e = %.4f (stop_at); continue with -v resume=1", phi))
  return
end
sim:write_dump("surface")
local plots = require("lib.plots")
if kiss then
  plots.run("econe", "--kiss=" .. kiss, out .. "/econe.csv", out .. "/econe.png")
else
  plots.run("econe", out .. "/econe.csv", out .. "/econe.png")
end
plots.run("render", out .. "/surface.h5", out .. "/shape.png")
os.remove(ckpt)
os.remove(ramp_ckpt)
os.remove(ramp_state)
local wall = slender.clock() - scene.t0
-- -v check=1 (the test suite): a kissing angle exists, after a two-winged (n = 2) shape
if slender.var("check", 0) == 1 then
  if not kiss then error("e-cone: no self-contact up to phi_e = " .. phi_max) end
  if wings_before ~= 2 then error("e-cone: " .. wings_before .. " wings before contact, expected 2") end
  if not (phi_ebmax > 0 and phi_ebmax < kiss) then error("e-cone: no E_b_hat maximum before contact") end
  -- the bending energy grows as A ln(r / R_C) outside a core smaller than the disc
  local rc = scene.core_radius()
  if not (rc > 0 and rc < 0.3) then error("e-cone: core radius " .. rc .. " outside (0, 0.3)") end
end
slender.result{h = h, edge = edge, inner = inner, nodes = nodes, triangles = tris,
               phi_kiss = kiss or -1, phi_kiss_lo = kiss_lo or -1,
               kiss_by = scene.contact and "contact" or "mid_surfaces",
               phi_Ebmax = phi_ebmax, Eb_hat_max = ebmax, wings_before_contact = wings_before,
               gamma_end = scene.cv("gamma"), R_C_end = scene.core_radius(), wall_s = wall,
               element_steps_per_s = tris * scene.steps_total / math.max(wall, 1e-9)}

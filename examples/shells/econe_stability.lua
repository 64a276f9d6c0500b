-- E-cone stability (docs/models.md §7.2 S-2): phi_e rises with static friction between the contacting
-- wings (the symmetric branch, contact planes at gamma = pi/2), friction is released at phi_top and the
-- cone relaxes to the skewed branch, which is then followed back down to the kissing angle. The critical
-- angle phi_crit, above which the symmetric cone does not survive the release, is bisected over the
-- checkpoints of the symmetric branch. Plots branches.png (E_b_hat and gamma of both branches) and
-- released.png (the cone released at phi_top, coloured by U_b).
-- Run time: -v fast=1 about 25 s; the default (h = 0.02, edge 1/16, phi_e to 10) about 40 min.
-- Options: -v h=0.02 -v edge=0.0625 -v phi_top=10 -v dphi=0.2 -v mu_static=2 -v out=DIR
--          -v gamma_drop=0.2 (a released cone has skewed when its contact-plane angle gamma fell by more
--          than this from the held one; where gamma is undefined, one contact zone on a coarse mesh,
--          when its nodes moved by more than -v moved=0.05 rms)
local slender = require("slender")

local fast = slender.var("fast", 0) == 1
local phi_top = slender.var("phi_top", fast and 6.0 or 10.0)
local dphi = slender.var("dphi", fast and 0.5 or 0.2)
local mu = slender.var("mu_static", 2.0)
local gamma_drop = slender.var("gamma_drop", 0.2)
local moved = slender.var("moved", 0.05)
local scene = require("lib.econe").build{fast = fast, out = "econe_stability_out", mu_static = mu}
local sim, relax, record, out = scene.sim, scene.relax, scene.record, scene.out
scene.open_log("branches.csv", {"branch"})

local function touching() return sim:value("contact/shell.far_contacts") > 0 end
local function gamma() return sim:value("contact/shell.gamma") end
local function positions()
  local x = {}
  for i = 1, scene.nodes do x[i] = {sim:position(i)} end
  return x
end
-- rms distance between the current nodes and a saved set
local function rms_from(x0)
  local s2 = 0
  for i = 1, scene.nodes do
    local x, y, z = sim:position(i)
    s2 = s2 + (x - x0[i][1]) ^ 2 + (y - x0[i][2]) ^ 2 + (z - x0[i][3]) ^ 2
  end
  return math.sqrt(s2 / scene.nodes)
end

-- 1. the symmetric branch, held by static friction once the wings touch
local up = {}  -- {phi, checkpoint, Eb_hat} of every touching state on the way up
local phi, kiss = 0, nil
while phi < phi_top - 1e-12 do
  phi = math.min(phi_top, phi + dphi)
  local steps = relax(phi)
  record(phi, steps, {"symmetric"})
  if touching() then
    kiss = kiss or phi
    local file = string.format("%s/symmetric_%02d.h5", out, #up + 1)
    sim:write_checkpoint(file)
    up[#up + 1] = {phi = phi, file = file, Eb_hat = sim:value("koiter.Eb_hat"), gamma = gamma()}
  end
end
if not kiss then error("e-cone stability: the wings never touched up to phi_e = " .. phi_top) end

-- 2. release the friction at phi_top: the skewed cone
local held = positions()
sim:modify("contact/shell", {mu_static = 0})
local steps = relax(phi_top)
record(phi_top, steps, {"released"})
local released_gamma, released_Eb, released_moved = gamma(), sim:value("koiter.Eb_hat"), rms_from(held)
print(string.format("released at phi_e = %.3f: nodes moved by %.4f (rms)", phi_top, released_moved))
sim:write_dump("surface")

-- 3. the skewed branch, followed down to the kissing angle (frictionless)
local down = {}
phi = phi_top
while phi > kiss + 1e-12 do
  phi = math.max(kiss, phi - dphi)
  steps = relax(phi)
  record(phi, steps, {"skewed"})
  down[#down + 1] = {phi = phi, Eb_hat = sim:value("koiter.Eb_hat"), gamma = gamma()}
end

-- 4. phi_crit: release the friction on a symmetric state and see whether it skews
local function skews(k)
  sim:read_checkpoint(up[k].file)
  local x0 = positions()
  sim:modify("contact/shell", {mu_static = 0})
  local n = relax(up[k].phi)
  record(up[k].phi, n, {"release_test"})
  local g, d = gamma(), rms_from(x0)
  print(string.format("release test at phi_e = %.3f: gamma %.3f -> %.3f, nodes moved by %.4f (rms)",
                      up[k].phi, up[k].gamma, g, d))
  -- two contact zones before and after, and the angle between their planes fell
  if up[k].gamma >= 0 and g >= 0 then return up[k].gamma - g > gamma_drop end
  return d > moved
end
local lo, hi = 0, #up  -- up[hi] skews (checked), up[lo] does not (0: below contact)
local crit
if skews(#up) then
  while hi - lo > 1 do
    local mid = (lo + hi) // 2
    if skews(mid) then hi = mid else lo = mid end
  end
  crit = {lo = lo > 0 and up[lo].phi or kiss - dphi, hi = up[hi].phi}
  print(string.format("symmetric cone unstable above phi_crit in (%.3f, %.3f]", crit.lo, crit.hi))
else
  print(string.format("the symmetric cone survives the release up to phi_top = %.3f", phi_top))
end
-- where the energies of the two branches cross: above it the skewed cone costs less bending
local cross
for _, d in ipairs(down) do  -- down runs from phi_top towards the kiss
  for _, u in ipairs(up) do
    if math.abs(u.phi - d.phi) < 1e-9 and u.Eb_hat < d.Eb_hat and not cross then cross = d.phi end
  end
end
if cross then print(string.format("the symmetric branch costs less bending energy below phi_e = %.3f", cross)) end
for _, u in ipairs(up) do os.remove(u.file) end
scene.csv:close()
local plots = require("lib.plots")
plots.run("branches", out .. "/branches.csv", out .. "/branches.png")
plots.run("render", out .. "/surface.h5", out .. "/released.png")

-- -v check=1 (the test suite): friction held a symmetric cone at phi_top that the release moves away,
-- while the cone at first contact stays where it is without friction
if slender.var("check", 0) == 1 then
  if not crit then error("e-cone stability: releasing the friction at phi_top did not move the cone") end
  if crit.lo < kiss then error("e-cone stability: the cone at first contact is already unstable") end
end
slender.result{h = scene.h, edge = scene.edge, mu_static = mu, phi_kiss_step = kiss,
               gamma_symmetric_top = up[#up].gamma, gamma_released = released_gamma,
               Eb_hat_symmetric_top = up[#up].Eb_hat, Eb_hat_skewed_top = released_Eb,
               moved_on_release = released_moved,
               phi_crit_lo = crit and crit.lo or -1, phi_crit_hi = crit and crit.hi or -1,
               phi_energy_cross = cross or -1,
               wall_s = slender.clock() - scene.t0}

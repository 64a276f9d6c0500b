-- E-cone (MODELS.md §7.2 S-1): a free disc grows circumferentially, phi_e ramped from 0 in steps with a
-- FIRE relaxation after each; records E_b_hat(phi_e), the energies, the number of wings and the first
-- self-contact ("kissing" excess angle, refined by bisection), then the contact-plane angle gamma.
-- Run time: -v fast=1 about 15 s; the default (h = 0.02, edge 1/16, phi_e to 12) about 10 min.
-- Options: -v h=0.02 -v edge=0.0625 -v phi_max=12 -v dphi=0.1 -v out=DIR -v boundary=mirror|combined
--          -v inner=0.25 grows a ring (annulus R_i <= r <= 1, both edges free; S-4) instead of a disc
--          -v mode=3 -v mode_amp=1e-3 starts from z = amp r^2 cos(3 phi) (the n = 3 e-cone of S-5)
local slender = require("slender")

local fast = slender.var("fast", 0) == 1
local h = slender.var("h", 0.02)
local edge = slender.var("edge", fast and 0.125 or 0.0625)
local phi_max = slender.var("phi_max", fast and 5.5 or 12.0)
local dphi = slender.var("dphi", fast and 0.5 or 0.1)
local kiss_bisections = slender.var("kiss_bisections", fast and 4 or 6)
local young, poisson = 1e4, 0.3
-- equilibrium: largest nodal force below ftol_rel * Y h edge^2 (the deck's tolerance)
local ftol = slender.var("ftol_rel", 1e-5) * young * h * edge * edge
local max_steps = slender.var("max_steps", 200000)
local out = slender.var("out", "econe_out")
os.execute("mkdir -p " .. out)

local sim = slender.simulation{dimension = 3, seed = slender.var("seed", 1)}
local inner = slender.var("inner", 0)
local noise = slender.var("noise", 1e-4)  -- out-of-plane noise amplitude (MODELS.md §6.12)
local nodes, tris
if inner > 0 then
  nodes, tris = sim:mesh{name = "disc", shape = "ring", radius = 1, inner_radius = inner, edge = edge,
                         noise = noise}
else
  nodes, tris = sim:mesh{name = "disc", shape = "disc", radius = 1, edge = edge, noise = noise}
end
-- an initial shape with n wings (S-5), on top of the random noise
local mode, mode_amp = slender.var("mode", 0), slender.var("mode_amp", 1e-3)
if mode > 0 then
  for i = 1, nodes do
    local x, y, z = sim:position(i)
    local r, a = math.sqrt(x * x + y * y), math.atan(y, x)
    sim:set_position(i, {x, y, z + mode_amp * r * r * math.cos(mode * a)})
  end
end
sim:growth("g", "econe", {phi_e = 0})
sim:shell("koiter", {mesh = "disc", thickness = h, young = young, poisson = poisson, growth = "g",
                     boundary = slender.var("boundary", "mirror")})
-- near neighbours (touching only across a ridge) within 4 h in the reference; the kissing
-- angle counts only contacts between triangles more than R/4 apart in the reference (the
-- wings): the sharp apex of a thick cone touches itself across the tip long before.
-- dense = "all" sums the forces of every feature pair within h: relaxations after contact
-- converge (with the closest pair only, FIRE stalls where the closest feature switches)
sim:pair("contact/shell", {mesh = "disc", thickness = h, young = young,
                           near_distance = slender.var("near_distance", 4 * h),
                           far_distance = slender.var("far_distance", 0.25),
                           dense = slender.var("dense", "all")})
sim:compute("rim", "rim_modes", {group = "disc.boundary", min_radius = 0.5 * (1 + inner)})
sim:integrator("fire", {})
sim:dump("surface", "shell", {file = out .. "/surface.h5", every = 1000000000, mesh = "disc",
                             faces = {"koiter.Ub", "koiter.Us", "contact/shell.contact"}})
print(string.format("e-cone: h = %g, %d nodes, %d triangles, ftol = %.3g", h, nodes, tris, ftol))

local csv = io.open(out .. "/econe.csv", "w")
csv:write("phi_e,E_s,E_b,Eb_hat,area,wings,a2,a3,contacts,far_contacts,gamma,steps,wall_s\n")
local t0 = slender.clock()
local function relax(phi)
  sim:modify("g", {phi_e = phi})
  local steps = sim:minimize{ftol = ftol, max_steps = max_steps}
  return steps
end
local function record(phi, steps)
  local row = {phi, sim:value("koiter.stretch"), sim:value("koiter.bend"), sim:value("koiter.Eb_hat"),
               sim:value("koiter.area"), sim:value("rim.n"), sim:value("rim.a2"), sim:value("rim.a3"),
               sim:value("contact/shell.contacts"), sim:value("contact/shell.far_contacts"),
               sim:value("contact/shell.gamma"), steps,
               slender.clock() - t0}
  for i, v in ipairs(row) do row[i] = string.format("%.8g", v) end
  csv:write(table.concat(row, ",") .. "\n")
  csv:flush()
  print(string.format("phi_e %.4f  Eb_hat %.4f  E_s/E_b %.3f  wings %d  contacts %d  gamma %.3f  steps %d",
                      phi, sim:value("koiter.Eb_hat"), sim:value("koiter.stretch") / sim:value("koiter.bend"),
                      sim:value("rim.n"), sim:value("contact/shell.contacts"),
                      sim:value("contact/shell.gamma"), steps))
end

local kiss, kiss_lo, wings_before = nil, nil, 0
local ebmax, phi_ebmax = -1, 0
local prev_phi, phi = 0, 0
local ckpt = out .. "/before_step.h5"
while phi < phi_max - 1e-12 do
  prev_phi = phi
  sim:write_checkpoint(ckpt)
  phi = math.min(phi_max, phi + dphi)
  local steps = relax(phi)
  if not kiss and sim:value("contact/shell.far_contacts") == 0 then wings_before = sim:value("rim.n") end
  if not kiss and sim:value("contact/shell.far_contacts") > 0 then
    -- first contact in (prev_phi, phi]: bisect from the last contact-free state
    local lo, hi = prev_phi, phi
    for _ = 1, kiss_bisections do
      local mid = 0.5 * (lo + hi)
      sim:read_checkpoint(ckpt)
      relax(mid)
      if sim:value("contact/shell.far_contacts") > 0 then
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
end
csv:close()
sim:write_dump("surface")
os.remove(ckpt)
local wall = slender.clock() - t0
-- -v check=1 (the test suite): a kissing angle exists, after a two-winged (n = 2) shape
if slender.var("check", 0) == 1 then
  if not kiss then error("e-cone: no self-contact up to phi_e = " .. phi_max) end
  if wings_before ~= 2 then error("e-cone: " .. wings_before .. " wings before contact, expected 2") end
  if not (phi_ebmax > 0 and phi_ebmax < kiss) then error("e-cone: no E_b_hat maximum before contact") end
end
slender.result{h = h, edge = edge, inner = inner, nodes = nodes, triangles = tris,
               phi_kiss = kiss or -1, phi_kiss_lo = kiss_lo or -1,
               phi_Ebmax = phi_ebmax, Eb_hat_max = ebmax, wings_before_contact = wings_before,
               gamma_end = sim:value("contact/shell.gamma"), wall_s = wall}

-- E-cone bifurcation (docs/models.md §7.2 S-2, §9.4): the symmetric n = 2 e-cone followed in
-- phi_e by pseudo-arc-length continuation on the exact Hessians, through the first self-contact,
-- with the count of unstable directions tracked; where it changes, the symmetric branch loses
-- stability, bisected on the arc length. Frictionless, from a perfect (noise-free, n = 2 seeded,
-- symmetrized) disc: the critical point is where the stiffness matrix turns indefinite, not a
-- friction-held release as in econe_stability.lua. Columns asym_x, asym_y, asym_turn: the rms
-- distance of the shape from its mirror images and from its half turn about the axis
-- (docs/shells/README.md). Writes OUT/bifurcation.csv.
-- Run time: -v fast=1 about 10 s; the default (h = 0.02, edge 1/16) about 2 min; refined cores
-- (-v refine_center=0.25 -v refine_levels=2) about 4 min.
-- Options: -v h=0.02 -v edge=0.0625 -v phi_start=5 (L-BFGS ramp to here, then continuation)
--          -v cont_ftol=1e-4 (the continuation's force tolerance, a fraction of the ramp's: a soft
--          asymmetric mode turns a looser residual into a visible asymmetry)
--          -v phi_end=9 -v ds=0.05 -v ds_max=0.1 -v noise=0 -v mode_amp=1e-3 -v out=DIR
--          -v symmetrize=1 (start from the mean of the relaxed cone's mirror images)
--          -v switch=1 (leave the symmetric branch at the bifurcation onto the new one)
--          -v stop_after=1 (critical points before the run stops; it also stops where the path
--          turns back below phi_start)
local slender = require("slender")

local fast = slender.var("fast", 0) == 1
-- a perfect disc seeded with the n = 2 shape (no random noise unless asked for), L-BFGS ramp
local scene = require("lib.econe").build{fast = fast, out = "econe_bifurcation_out", mu_static = 0,
                                         noise = 0, mode = 2, minimizer = "lbfgs"}
local sim, relax, out = scene.sim, scene.relax, scene.out
local phi_start = slender.var("phi_start", fast and 4.0 or 5.0)
local phi_end = slender.var("phi_end", fast and 6.5 or 9.0)
local dphi = slender.var("dphi", 0.5)

-- the mirror images of every node in the reference (the disc mesh is symmetric under both
-- reflections): the rms distance of the shape from its mirror images tells which symmetry a
-- state breaks (the symmetric cone has none; the skewed cone breaks both reflections)
local mirror_x, mirror_y = {}, {}
local X = {}  -- the start (the flat disc seeded with the n = 2 shape)
for i = 1, scene.nodes do X[i] = {sim:position(i)} end
-- the node of the start nearest (tx, ty) in the plane, and its squared distance
local function nearest(tx, ty)
  local best, bd = nil, math.huge
  for j = 1, scene.nodes do
    local d = (X[j][1] - tx) ^ 2 + (X[j][2] - ty) ^ 2
    if d < bd then best, bd = j, d end
  end
  return best, bd
end
for i = 1, scene.nodes do
  local jx, dx = nearest(-X[i][1], X[i][2])
  local jy, dy = nearest(X[i][1], -X[i][2])
  if dx > 1e-12 or dy > 1e-12 then error("e-cone bifurcation: the mesh is not mirror symmetric") end
  mirror_x[i], mirror_y[i] = jx, jy
end
-- rms distance of the shape from its image under a mirror (axis 1: x -> -x, 2: y -> -y) or,
-- with axis 0, under the half turn about z (both mirrors)
local function asymmetry(map, axis)
  local s2 = 0
  for i = 1, scene.nodes do
    local x = {sim:position(i)}
    local j = axis == 0 and mirror_x[mirror_y[i]] or map[i]
    local y = {sim:position(j)}
    if axis == 0 then
      y[1], y[2] = -y[1], -y[2]
    else
      y[axis] = -y[axis]
    end
    s2 = s2 + (x[1] - y[1]) ^ 2 + (x[2] - y[2]) ^ 2 + (x[3] - y[3]) ^ 2
  end
  return math.sqrt(s2 / scene.nodes)
end

-- 1. the ramp to phi_start by L-BFGS relaxations (the n = 2 cone forms on the way)
local phi = 0
while phi < phi_start - 1e-12 do
  phi = math.min(phi_start, phi + dphi)
  relax(phi)
end
print(string.format("ramp to phi_e = %.3f: Eb_hat %.4f, wings %d, %.1f s", phi, sim:value("koiter.Eb_hat"),
                    sim:value("rim.n"), slender.clock() - scene.t0))

-- the relaxed cone made exactly symmetric (the mean of its four mirror images): the discrete
-- forces are mirror-equivariant to round-off, but the ramp's tolerance leaves a residual that a
-- soft asymmetric mode turns into a visible asymmetry; from an exactly symmetric start the
-- path stays on the symmetric branch until it loses stability
local function symmetrize()
  local x = {}
  for i = 1, scene.nodes do x[i] = {sim:position(i)} end
  for i = 1, scene.nodes do
    local a, b, c = x[mirror_x[i]], x[mirror_y[i]], x[mirror_x[mirror_y[i]]]
    sim:set_position(i, {(x[i][1] - a[1] + b[1] - c[1]) / 4, (x[i][2] + a[2] - b[2] - c[2]) / 4,
                         (x[i][3] + a[3] + b[3] + c[3]) / 4})
  end
end
if slender.var("symmetrize", 1) == 1 then symmetrize() end

-- 2. hold the rigid motions with six components and nothing more (an isostatic support of a
-- free body carries no reaction, so equilibria and their stability are those of the free cone
-- less its six zero modes). The components are ones the symmetric cone keeps at zero (its
-- mirror planes x = 0 and y = 0), so following it needs no rigid correction that would itself
-- break the symmetry: the apex in x, y and z (z: a translation along the axis, which both
-- mirrors keep); the rim nodes on the +x and -x axes in y; the rim node on the +y axis in x.
-- (nodes chosen by their place in the flat start, not where the ramp moved them)
sim:group("hold_apex", {nodes = {(nearest(0, 0))}})
sim:group("hold_xaxis", {nodes = {(nearest(2, 0)), (nearest(-2, 0))}})
sim:group("hold_yaxis", {nodes = {(nearest(0, 2))}})
sim:fix("apex", "clamp", {group = "hold_apex", components = "xyz"})
sim:fix("rim_x", "clamp", {group = "hold_xaxis", components = "y"})
sim:fix("rim_y", "clamp", {group = "hold_yaxis", components = "x"})

-- the start converged by Newton with its line search (the continuation's own start takes full
-- Newton steps, which a residual of the ramp's tolerance on a finely refined apex can throw far)
local cont_ftol = scene.ftol * slender.var("cont_ftol", 1e-4)
sim:minimize{method = "newton", ftol = cont_ftol, max_steps = 100}

-- 3. continuation in phi_e
local csv = assert(io.open(out .. "/bifurcation.csv", "w"))
csv:write("point,phi_e,negative_pivots,iterations,ds,event,critical_phi_e,Eb_hat,E_s,far_contacts," ..
          "gamma,mid_gap,a2,a3,asym_x,asym_y,asym_turn,wall_s\n")
local crit = {}
-- stop after this many critical points (with switch=1: 20 points onto the new branch)
local stop_after = slender.var("stop_after", 1)
local switch = slender.var("switch", 0) == 1
local crit_point, start_unstable, contacts_at_crit = nil, nil, nil
local asym_before = 0  -- largest asymmetry before the first critical point
local prev_phi, kiss_lo, kiss_hi = nil, nil, nil  -- the first far contact lies in (kiss_lo, kiss_hi]
local points, last = sim:continuation{
  load = "g", lambda0 = phi, lambda_max = phi_end, lambda_min = phi - 1e-9,
  ds = slender.var("ds", 0.05), ds_max = slender.var("ds_max", 0.1), ds_min = 1e-6,
  ftol = cont_ftol, points = slender.var("points", 400), switch_branch = switch,
  callback = function(_, p)
    if p.index == 0 then start_unstable = p.negative_pivots end
    if not kiss_hi and scene.cv("far_contacts") > 0 then kiss_lo, kiss_hi = prev_phi or -1, p.lambda end
    prev_phi = p.lambda
    if p.event then
      contacts_at_crit = contacts_at_crit or scene.cv("far_contacts")
      crit[#crit + 1] = {event = p.event, phi = p.critical_lambda}
      crit_point = crit_point or p.index
    end
    local ax, ay, at = asymmetry(mirror_x, 1), asymmetry(mirror_y, 2), asymmetry(nil, 0)
    if not crit_point and not p.event then asym_before = math.max(asym_before, ax, ay) end
    csv:write(string.format("%d,%.8g,%d,%d,%.5g,%s,%.8g,%.8g,%.8g,%d,%.6g,%.6g,%.6g,%.6g,%.4g,%.4g,%.4g,%.2f\n", p.index,
                            p.lambda, p.negative_pivots, p.iterations, p.ds, p.event or "",
                            p.critical_lambda or p.lambda, sim:value("koiter.Eb_hat"), sim:value("koiter.stretch"),
                            scene.cv("far_contacts"), scene.cv("gamma"), sim:value("gap.distance"),
                            sim:value("rim.a2"), sim:value("rim.a3"), ax, ay, at, slender.clock() - scene.t0))
    csv:flush()
    print(string.format("point %3d  phi_e %.5f  unstable %d  iterations %d  Eb_hat %.5f  far contacts %d  gamma %.3f  asym %.2g %.2g %.2g%s",
                        p.index, p.lambda, p.negative_pivots, p.iterations, sim:value("koiter.Eb_hat"),
                        scene.cv("far_contacts"), scene.cv("gamma"), ax, ay, at,
                        p.event and string.format("  <- %s at phi_e = %.6f", p.event, p.critical_lambda) or ""))
    return #crit >= stop_after and (not switch or p.index >= crit_point + 20)
  end}
csv:close()
for _, c in ipairs(crit) do print(string.format("%s at phi_e = %.6f", c.event, c.phi)) end
-- -v check=1 (the test suite): the path starts stable, keeps both mirror symmetries to round-off,
-- and its first critical point is a bifurcation (a limit point would turn phi_e back)
if slender.var("check", 0) == 1 then
  if start_unstable ~= 0 then error("e-cone bifurcation: the relaxed cone at phi_start is unstable") end
  if not crit[1] then error("e-cone bifurcation: no critical point up to phi_e = " .. last) end
  if crit[1].event ~= "bifurcation point" then error("e-cone bifurcation: first event " .. crit[1].event) end
  if asym_before > 1e-9 then
    error(string.format("e-cone bifurcation: the path left the symmetric branch before it lost stability " ..
                        "(asymmetry %.3g)", asym_before))
  end
end
slender.result{h = scene.h, edge = scene.edge, phi_start = phi, points = points, phi_last = last,
               first_critical = crit[1] and crit[1].phi or -1,
               first_kind = crit[1] and crit[1].event:gsub(" ", "_") or "none",
               far_contacts_at_critical = contacts_at_crit or -1, asymmetry_before = asym_before,
               kiss_lo = kiss_lo or -1, kiss_hi = kiss_hi or -1,
               wall_s = slender.clock() - scene.t0}

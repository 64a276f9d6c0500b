-- Purpose: cylindrical bending of a Koiter shell (docs/models.md §6): a flat strip wrapped isometrically on a
-- cylinder of radius rho stores the bending energy D kappa^2 A / 2 (kappa = 1/rho, D = Y h^3 / (12 (1 - nu^2)),
-- A = L W; Timoshenko & Woinowsky-Krieger, "Theory of Plates and Shells", §2, pure bending into a cylinder).
-- The shell's energy is evaluated on the wrapped control net (free ghosts wrapped with it), no relaxation.
-- Expected run time: under a second at n = 32 (cells along the strip); the defaults are the fast mode
-- (-v fast=1 changes nothing).
--   slender cylinder_bend.lua -v n=16
local slender = require("slender")
local n = slender.var("n", 16)
local L, W, h, Y, nu, rho = 1.0, 0.5, 0.01, 1e4, 0.3, 1.0
local D = Y * h ^ 3 / (12 * (1 - nu * nu))

local sim = slender.simulation { dimension = 3, quiet = true }
sim:mesh { name = "strip", shape = "rectangle", size = { L, W }, edge = L / n }
sim:shell("koiter", { mesh = "strip", thickness = h, young = Y, poisson = nu, boundary = "free_ghosts" })
sim:integrator("fire", {})
local t0 = slender.clock()
for i = 1, sim:nnodes() do  -- every node, ghosts included
  local x, y = sim:position(i)
  local s = x - 0.5 * L
  sim:set_position(i, { rho * math.sin(s / rho), y, rho * (1 - math.cos(s / rho)) })
end
sim:run { steps = 0 }
local eb, es = sim:value("koiter.bend"), sim:value("koiter.stretch")
local wall = slender.clock() - t0
local ref = 0.5 * D / rho ^ 2 * L * W
local err = math.abs(eb / ref - 1)
print(string.format("cylinder n=%d: E_b = %.6e, reference %.6e, error %.3e, E_s/E_b = %.2e", n, eb, ref, err,
                    es / eb))
slender.result { case = "cylinder_bend", n = n, nodes = sim:nnodes(), E_b = eb, ref = ref, rel_error = err,
                 stretch_over_bend = es / eb, wall_s = wall }
local check = slender.var("check", 0)
if check > 0 then
  assert(err < check, string.format("relative error %.3e exceeds the tolerance %.3e", err, check))
end

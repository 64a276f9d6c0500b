-- Purpose: a cantilever shell strip (Koiter shell on Loop subdivision, docs/models.md §6) clamped
-- at its root edge at second order (`clamped_edges`) and loaded at its tip edge by an end
-- shear (a line load, `line_load`), against the elastica: the large-deflection benchmark of
-- the statics issue, solved by Newton (docs/models.md §9).
-- Expected run time: < 1 s at n = 2 (cells across the width), ~3 s at n = 4, ~30 s at n = 8.
--
-- The strip: L = 10, b = 1, h = 0.1, E = 1.2e6, nu = 0 (so the plate is a beam: EI = E b h^3 / 12
-- = 100), end shear P = 4 spread over the tip edge (P L^2 / EI = 4). Reference tip displacement
-- (-u, w) = (3.2893, 6.7006): the elastica of a cantilever under a dead end load, computed
-- by lib/elastica.lua (shooting on the clamped-free elastica) and printed beside the result.
-- The load is applied in `steps` equal increments, each solved by Newton.
--   slender shell_strip.lua -v n=4 [-v steps=4] [-v clamp=rows]
-- -v clamp=rows holds three rows of control nodes at the root instead (the `clamp` fix way,
-- first order: the comparison the second-order edge rule was built for).
local slender = require("slender")
local elastica = require("lib.elastica")
local n = slender.var("n", 2)
local clamp = slender.var("clamp", "edge")
local L, b, h, Y = 10.0, 1.0, 0.1, 1.2e6
local EI = Y * b * h ^ 3 / 12
local P = 4.0
local e = b / n

local sim = slender.simulation { dimension = 3, quiet = slender.var("quiet", 1) == 1 }
local nodes, tris = sim:mesh { name = "strip", shape = "rectangle", size = { L, b }, edge = e }
local tol = 1e-6 * e
sim:region("tip_edge", "box", { lo = { L - tol, -tol, -tol }, hi = { L + tol, b + tol, tol } })
sim:group("tip", { region = "tip_edge" })
local shell = { mesh = "strip", thickness = h, young = Y, poisson = 0.0, boundary = "mirror",
                line_load = { 0, 0, P / b }, line_load_edges = { "tip" } }
if clamp == "edge" then
  sim:region("root_edge", "box", { lo = { -tol, -tol, -tol }, hi = { tol, b + tol, tol } })
  sim:group("root", { region = "root_edge" })
  shell.clamped_edges = { "root" }
elseif clamp == "rows" then
  sim:region("root_rows", "box", { lo = { -tol, -tol, -tol }, hi = { 2 * (L / math.ceil(L / e)) + tol, b + tol, tol } })
  sim:group("root", { region = "root_rows" })
else
  error("clamp must be edge or rows")
end
sim:shell("koiter", shell)
if clamp == "rows" then sim:fix("clamp", "clamp", { group = "root" }) end
sim:compute("tip", "limit_point", { mesh = "strip", point = { L, b / 2, 0 } })
sim:integrator("fire", {})

local t0 = slender.clock()
local iterations = sim:minimize { method = "newton", ftol = 1e-9 * P / n, max_steps = 500 }
local wall = slender.clock() - t0
local u, w = -sim:value("tip.ux"), sim:value("tip.uz")
-- the extensible elastica (EA = E b h: with nu = 0 the strip's membrane stiffness)
local x_tip, y_tip = elastica.cantilever_tip(P, EI, Y * b * h, L)
local u_ref, w_ref = L - x_tip, -y_tip
local err = math.sqrt((u - u_ref) ^ 2 + (w - w_ref) ^ 2) / L
print(string.format("strip n=%d (%s clamp): tip (-u, w) = (%.5f, %.5f), elastica (%.5f, %.5f), error %.3e L, "
                    .. "%d Newton iterations, %.2f s", n, clamp, u, w, u_ref, w_ref, err, iterations, wall))
local check = slender.var("check", 0)
if check > 0 and not (err < check) then
  error(string.format("strip error %.3e above the check %.3e", err, check))
end
slender.result { case = "shell_strip", clamp = clamp, n = n, nodes = nodes, triangles = tris, u = u, w = w,
                 u_ref = u_ref, w_ref = w_ref, error = err, rel_error = err, steps = iterations, wall_s = wall }

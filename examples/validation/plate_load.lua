-- Purpose: a square Kirchhoff plate under a uniform load, simply supported or clamped, against the
-- classical centre deflection w = alpha q a^4 / D (Koiter shell on Loop subdivision, docs/models.md §6;
-- static equilibrium by FIRE, or by L-BFGS with -v integrator=lbfgs, or by Newton with
-- -v integrator=newton).
-- Expected run time: ~2 s at n = 8, ~10 s at n = 16, ~2 min at n = 32 (cells per side).
--
-- References: simply supported, Navier's double series (Timoshenko & Woinowsky-Krieger, "Theory of
-- Plates and Shells", 2nd ed., §30, eq. 139), alpha = 16/pi^6 sum_{m,n odd} (-1)^((m+n)/2-1) /
-- (m n (m^2+n^2)^2) = 0.00406235, summed below; clamped, alpha = 0.00126532 (the same book's
-- Table 35 prints 0.00126; the digits from Taylor & Govindjee, Commun. Numer. Meth. Engng 20
-- (2004) 757; independent of nu). The deflection is small (w / h = 1e-2), so the nonlinear
-- shell is in its linear range. support = clamped holds three rows of nodes (the `boundary`
-- rule, first order); clamped_edges clamps every edge at second order (`clamped_edges`).
--   slender plate_load.lua -v n=16 -v support=clamped_edges -v integrator=newton
local slender = require("slender")
local n = slender.var("n", 8)
local support = slender.var("support", "simply_supported")
local a, h, Y, nu = 1.0, 0.01, 1e4, 0.3
local D = Y * h ^ 3 / (12 * (1 - nu * nu))

local alpha
if support == "simply_supported" then
  alpha = 0
  for i = 1, 399, 2 do
    for j = 1, 399, 2 do
      local sign = (((i - 1) // 2 + (j - 1) // 2) % 2 == 0) and 1 or -1
      alpha = alpha + sign / (i * j * (i * i + j * j) ^ 2)
    end
  end
  alpha = alpha * 16 / math.pi ^ 6
elseif support == "clamped" or support == "clamped_edges" then
  alpha = 0.00126532
else
  error("support must be simply_supported, clamped or clamped_edges")
end
local w_ref = 0.01 * h          -- target deflection, sets the load
local q = w_ref * D / (alpha * a ^ 4)

local sim = slender.simulation { dimension = 3, quiet = slender.var("quiet", 1) == 1 }
local nodes, tris = sim:mesh { name = "plate", shape = "rectangle", size = { a, a }, edge = a / n }
-- clamped_edges: every edge of the mesh (its boundary nodes, group "plate.boundary") clamped at
-- second order
local shell = { mesh = "plate", thickness = h, young = Y, poisson = nu, boundary = support, load = { 0, 0, q } }
if support == "clamped_edges" then shell.boundary, shell.clamped_edges = "mirror", { "plate.boundary" } end
sim:shell("koiter", shell)
sim:compute("centre", "limit_point", { mesh = "plate", point = { a / 2, a / 2, 0 } })
sim:integrator("fire", {})
local t0 = slender.clock()
local method = slender.var("integrator", "fire")
local steps = sim:minimize { ftol = slender.var("ftol_rel", 1e-6) * q * (a / n) ^ 2, max_steps = 2000000,
                             method = method, memory = slender.var("memory", 50),
                             -- -v precondition=hessian: L-BFGS on the factorised exact Hessian
                             precondition = method == "lbfgs" and slender.var("precondition", "none") or nil }
local wall = slender.clock() - t0
local w = sim:value("centre.uz")
local err = math.abs(w / w_ref - 1)
print(string.format("plate %s n=%d: w = %.6e, reference %.6e, error %.3e, %d %s iterations, %.2f s",
                    support, n, w, w_ref, err, steps, method, wall))
local check = slender.var("check", 0)
if check > 0 and not (err < check) then
  error(string.format("plate error %.3e above the check %.3e", err, check))
end
slender.result { case = "plate_load", method = method, support = support, n = n, nodes = nodes, triangles = tris,
                 w = w, w_ref = w_ref, error = err, rel_error = err, steps = steps, wall_s = wall,
                 element_steps_per_s = tris * steps / math.max(wall, 1e-9) }

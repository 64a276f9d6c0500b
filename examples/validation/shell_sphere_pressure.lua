-- Purpose: a closed spherical shell (Koiter shell on Loop subdivision, docs/models.md §6)
-- inflated by a follower pressure (`pressure`), solved by Newton, against the exact
-- uniform inflation of a Koiter sphere; the check of the pressure load and its Hessian.
-- Expected run time: < 1 s at levels 1 and 2, ~2 s at level 3, ~35 s at level 4.
--
-- The sphere: R = 1, h = 0.01, Y = 1e4, nu = 0.3, internal pressure p = 3 (the linear
-- membrane answer w = p R^2 (1 - nu) / (2 Y h) = 0.0105). Uniform inflation to radius r
-- stretches the mid-surface by e = ((r/R)^2 - 1)/2 in every direction and bends it by
-- b = -(r - R)/R^2, so the energy is 4 pi R^2 (1 + nu) (C_m e^2 + C_b b^2) - p 4/3 pi r^3
-- (C_m = Y h / (1 - nu^2), C_b = Y h^3 / (12 (1 - nu^2))); its stationary point,
--   2 (1 + nu) (C_m e r - C_b b) = p r^2,
-- solved by Newton below, is the reference. The shell's radius is read from the volume
-- its limit surface encloses, r = (3 V / 4 pi)^(1/3), against the same at p = 0 (the limit
-- surface of the control net lies inside the unit sphere). Six components hold the rigid
-- motions without resisting inflation: the poles in x and y, the point (R, 0, 0) in y and z.
--   slender shell_sphere_pressure.lua -v level=2 [-v pressure=3]
local slender = require("slender")
local level = slender.var("level", 2)
local R, h, Y, nu = 1.0, 0.01, 1e4, 0.3
local p = slender.var("pressure", 3.0)

local sim = slender.simulation { dimension = 3, quiet = slender.var("quiet", 1) == 1 }
-- level 1 is the icosahedron refined once (80 triangles); each level refines once more
local nodes, tris = sim:mesh { name = "ball", shape = "sphere", radius = R, edge = 2 * R, refine = level - 1 }
local tol = 1e-6
local function pin(name, at, components)
  sim:region(name, "box", { lo = { at[1] - tol, at[2] - tol, at[3] - tol }, hi = { at[1] + tol, at[2] + tol, at[3] + tol } })
  sim:group(name, { region = name })
  sim:fix(name, "clamp", { group = name, components = components })
end
pin("north", { 0, 0, R }, "xy")
pin("south", { 0, 0, -R }, "xy")
pin("east", { R, 0, 0 }, "yz")
sim:shell("koiter", { mesh = "ball", thickness = h, young = Y, poisson = nu, pressure = p })
sim:integrator("fire", {})

local function radius() return (3 * sim:value("koiter.volume") / (4 * math.pi)) ^ (1 / 3) end
sim:run(0) -- evaluates the forces once, so the volume at rest is known
local r0 = radius()
local t0 = slender.clock()
local iterations = sim:minimize { method = "newton", ftol = 1e-10 * p, max_steps = 200 }
local wall = slender.clock() - t0
local w = radius() - r0

-- the reference: Newton on 2 (1 + nu) (C_m e r - C_b b) - p r^2 = 0
local Cm, Cb = Y * h / (1 - nu ^ 2), Y * h ^ 3 / (12 * (1 - nu ^ 2))
local r = R + p * R ^ 2 * (1 - nu) / (2 * Y * h)
for _ = 1, 50 do
  local e, b = 0.5 * ((r / R) ^ 2 - 1), -(r - R) / R ^ 2
  local g = 2 * (1 + nu) * (Cm * e * r - Cb * b) - p * r ^ 2
  local dg = 2 * (1 + nu) * (Cm * (e + r * r / R ^ 2) + Cb / R ^ 2) - 2 * p * r
  r = r - g / dg
end
local w_ref = r - R
local err = math.abs(w - w_ref) / w_ref
print(string.format("sphere level %d (%d nodes, %d triangles): w = %.7f, reference %.7f (linear %.7f), "
                    .. "error %.3e, %d Newton iterations, %.2f s", level, nodes, tris, w, w_ref,
                    p * R ^ 2 * (1 - nu) / (2 * Y * h), err, iterations, wall))
local check = slender.var("check", 0)
if check > 0 and not (err < check) then
  error(string.format("sphere error %.3e above the check %.3e", err, check))
end
slender.result { case = "shell_sphere_pressure", level = level, nodes = nodes, triangles = tris, w = w,
                 w_ref = w_ref, error = err, rel_error = err, steps = iterations, wall_s = wall }

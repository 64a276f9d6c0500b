-- Growth from a deck function (docs/models.md §7.3): a free rectangle with uniaxial growth
-- G = diag(1.2, 1) relaxes to the stretched rectangle, stress-free and flat; the same
-- function written as a scalar reproduces the isotropic growth style.
local slender = require("slender")

local function relaxed(growth_style, params)
  local sim = slender.simulation { dimension = 3, quiet = true }
  local n = sim:mesh { name = "r", shape = "rectangle", size = { 1.0, 0.5 }, edge = 0.125 }
  sim:growth("g", growth_style, params)
  sim:shell("koiter", { mesh = "r", thickness = 0.02, growth = "g", boundary = "mirror" })
  -- limit-surface points (a control node is not on the surface) on opposite edges
  local pts = { w = { 0, 0.25, 0 }, e = { 1, 0.25, 0 }, s = { 0.5, 0, 0 }, n = { 0.5, 0.5, 0 } }
  for k, p in pairs(pts) do sim:compute(k, "limit_point", { mesh = "r", point = p }) end
  sim:integrator("fire", {})
  sim:minimize { ftol = 1e-10, max_steps = 200000 }
  local function pos(k) return { sim:value(k .. ".x"), sim:value(k .. ".y"), sim:value(k .. ".z") } end
  local function dist(a, b) return math.sqrt((a[1] - b[1]) ^ 2 + (a[2] - b[2]) ^ 2 + (a[3] - b[3]) ^ 2) end
  local zmax = 0
  for i = 1, n do zmax = math.max(zmax, math.abs(select(3, sim:position(i)))) end
  return dist(pos("w"), pos("e")), dist(pos("s"), pos("n")), zmax, sim:value("koiter.energy")
end

local lx, ly, z, e = relaxed("function", { fn = function(x, y, zz, t) return { 1.2, 0, 0, 1 } end })
print(string.format("uniaxial: %.10f x %.10f, |z| %.2e, energy %.2e", lx, ly, z, e))
-- the limit points of the edge nodes sit inside the rectangle: compare with their reference distances
local function ref_dist()
  local sim = slender.simulation { dimension = 3, quiet = true }
  sim:mesh { name = "r", shape = "rectangle", size = { 1.0, 0.5 }, edge = 0.125 }
  sim:compute("w", "limit_point", { mesh = "r", point = { 0, 0.25, 0 } })
  sim:compute("e", "limit_point", { mesh = "r", point = { 1, 0.25, 0 } })
  sim:compute("s", "limit_point", { mesh = "r", point = { 0.5, 0, 0 } })
  sim:compute("n", "limit_point", { mesh = "r", point = { 0.5, 0.5, 0 } })
  return sim:value("e.x") - sim:value("w.x"), sim:value("n.y") - sim:value("s.y")
end
local rx, ry = ref_dist()
print(string.format("reference limit distances %.10f x %.10f", rx, ry))
assert(math.abs(lx - 1.2 * rx) < 1e-7 and math.abs(ly - ry) < 1e-7, "not the stretched rectangle")
assert(z < 1e-9 and e < 1e-12, "not flat and stress-free")

local a = { relaxed("function", { fn = function() return 1.1 end }) }
local b = { relaxed("isotropic", { factor = 1.1 }) }
for k = 1, 2 do assert(math.abs(a[k] - b[k]) < 1e-9, "function and isotropic growth differ") end
print("growth function: ok")

-- Purpose: the Scordelis–Lo roof (Koiter shell on Loop subdivision, docs/models.md §6): a
-- cylindrical roof under its own weight on rigid diaphragms (`diaphragm_edges`), free along
-- its straight edges, solved by Newton; the vertical deflection of the middle of a free edge
-- against the Kirchhoff–Love reference 0.3006.
-- Expected run time: < 1 s at n = 4 and 8, ~1 s at n = 16, ~8 s at n = 32, ~1 min at n = 64.
--
-- The roof (MacNeal & Harder's shell obstacle course): radius R = 25, length L = 50 along x,
-- the arc +-40 degrees about the crown (z up), thickness t = 0.25, E = 4.32e8, nu = 0, self
-- weight 90 per area downwards. The ends x = +-L/2 rest on diaphragms, rigid in their plane
-- (u_y = u_z = 0) and free along x; the middle of the crown holds x against sliding. The reference, 0.3006 downwards at (0, R sin 40, R cos 40),
-- is the linear Kirchhoff–Love value (Kiendl et al. 2009, isogeometric Kirchhoff–Love
-- shells; 0.3024 with transverse shear). slender's Koiter shell is geometrically nonlinear,
-- so the deck applies the weight scaled by `scale` (1e-3) and divides the deflection by it:
-- the linear response. The mesh is n x n cells (2n along x and along the arc for the whole
-- roof), written as an OFF file and read by sim:mesh. The free edges have free ghosts (the
-- ghost nodes are unknowns, so the free-edge conditions come out of the energy); -v
-- free_edge=mirror places them by the mirror rule instead, which converges at first order
-- here (docs/models.md §6.7).
--   slender scordelis_lo.lua -v n=8 [-v scale=1e-3] [-v free_edge=mirror] [-v check=0.02]
local slender = require("slender")
local n = slender.var("n", 8)
local scale = slender.var("scale", 1e-3)
local R, L, t, E, q = 25.0, 50.0, 0.25, 4.32e8, 90.0
local half = math.rad(40)
local w_ref = 0.3006

local nx, ny = 2 * n, 2 * n
local stem = os.tmpname() -- a fresh name; the mesh goes beside it with the .off extension
local path = stem .. ".off"
do
  local fh = assert(io.open(path, "w"))
  fh:write(string.format("OFF\n%d %d 0\n", (nx + 1) * (ny + 1), 2 * nx * ny))
  for i = 0, nx do
    for j = 0, ny do
      local x, th = -L / 2 + L * i / nx, -half + 2 * half * j / ny
      fh:write(string.format("%.17g %.17g %.17g\n", x, R * math.sin(th), R * math.cos(th)))
    end
  end
  local function id(i, j) return i * (ny + 1) + j end
  for i = 0, nx - 1 do
    for j = 0, ny - 1 do
      local a, b, c, d = id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)
      fh:write(string.format("3 %d %d %d\n3 %d %d %d\n", a, b, c, a, c, d))
    end
  end
  fh:close()
end

local sim = slender.simulation { dimension = 3, quiet = slender.var("quiet", 1) == 1 }
local nodes, tris = sim:mesh { name = "roof", file = path }
os.remove(path)
os.remove(stem)
local tol = 1e-6
sim:region("end_lo", "box", { lo = { -L / 2 - tol, -R, -R }, hi = { -L / 2 + tol, R, 2 * R } })
sim:region("end_hi", "box", { lo = { L / 2 - tol, -R, -R }, hi = { L / 2 + tol, R, 2 * R } })
sim:group("ends", { region = "end_lo" })
sim:group("ends_hi", { region = "end_hi" })
-- the diaphragms leave the roof free to slide along x: the crown's middle node holds x (where
-- the symmetric answer has u_x = 0 anyway), or the stiffness matrix is singular
sim:region("crown", "box", { lo = { -tol, -tol, R - tol }, hi = { tol, tol, R + tol } })
sim:group("crown", { region = "crown" })
sim:fix("axial", "clamp", { group = "crown", components = "x" })
sim:shell("koiter", { mesh = "roof", thickness = t, young = E, poisson = 0.0, boundary = slender.var("free_edge", "free_ghosts"),
                      diaphragm_edges = { "ends", "ends_hi" }, load = { 0, 0, -q * scale } })
sim:compute("edge_mid", "limit_point", { mesh = "roof", point = { 0, R * math.sin(half), R * math.cos(half) } })
sim:integrator("fire", {})

local t0 = slender.clock()
local iterations = sim:minimize { method = "newton", ftol = 1e-4 * q * scale * L * R / (nx * ny), max_steps = 50 }
local wall = slender.clock() - t0
local w = -sim:value("edge_mid.uz") / scale
local err = math.abs(w - w_ref) / w_ref
print(string.format("Scordelis-Lo n=%d (%d nodes, %d triangles): free-edge midpoint deflection %.5f, reference %.4f, "
                    .. "error %.3e, %d Newton iterations, %.2f s", n, nodes, tris, w, w_ref, err, iterations, wall))
local check = slender.var("check", 0)
if check > 0 and not (err < check) then
  error(string.format("Scordelis-Lo error %.3e above the check %.3e", err, check))
end
slender.result { case = "scordelis_lo", n = n, nodes = nodes, triangles = tris, w = w, w_ref = w_ref, error = err,
                 rel_error = err, steps = iterations, wall_s = wall }

-- Purpose: the high-torsion packing (MODELS.md §4, §4.5, §5; thesis ch. 4): a
-- precurved rod with frames (quaternion Cosserat rod) whose rotation is held in the
-- nozzle, so torsion builds up as it is fed into the sphere; stop at the force
-- threshold of lib/scene.lua.
-- Expected run time: R = 4 (fast mode, -v R=4): ~20 s; R = 10: tens of minutes.
-- Thesis parameters: a = 1, Y = 1000, nu = 0.33, mu_s = 0.2, mu_d = 0.18, intrinsic
-- radius of curvature R_i = 100 (kbar = (0, 1/R_i, 0), MODELS.md §4.5: the thesis'
-- "k_y = 0.001" contradicts its R_i = 100; -v R_i=1000 runs that reading).
local R_i = slender.var("R_i", 100.0)
require("lib.scene").run { name = "high_torsion", R = 10, rotation = "held",
  bend = function(sim, k)
    local nu = 0.33
    local J = math.pi / 2          -- polar moment of a unit-radius section
    local G = 1000 / (2 * (1 + nu))
    sim:bond("rod/cosserat", { YI = k.YI, GJ = G * J, coupling = k.YA, rest_curvature = { 0, 1 / R_i, 0 },
                               rot_inertia = 1.0 * J,   -- rho J, rho = 1
                               node_energy = true })
  end }

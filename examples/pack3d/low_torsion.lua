-- Purpose: the low-torsion packing (MODELS.md §3, §5; thesis ch. 4): a naturally
-- straight rod, free to twist, modelled as a discrete elastic rod without directors,
-- fed through a nozzle into a sphere until the injection force reaches 0.01 YA.
-- Expected run time: R = 4 (fast mode, -v R=4): ~1 s; R = 10: ~4 min (projected: 15 min with
-- Gear q = 6, 3.5x fewer steps with adaptive Verlet); R = 20: ~2 h projected (7.4 h and 63.1 M
-- Gear steps to its jam at phi = 0.452).
-- Thesis parameters: a = 1, Y = 1000, nu = 0.33, mu_s = 0.2, mu_d = 0.18; R in
-- {4, 5, 10, 13, 20, 40, 50}.
require("lib.scene").run { name = "low_torsion", R = 10, jam_time = 2.418,
  bend = function(sim, k) sim:bond("rod/straight", { YI = k.YI, node_energy = true }) end }

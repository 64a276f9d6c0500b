-- Purpose: the low-torsion packing (docs/models.md §3, §5; thesis ch. 4): a naturally
-- straight rod, free to twist, modelled as a discrete elastic rod without directors,
-- fed through a nozzle into a sphere until the injection force reaches 0.01 YA.
-- Expected run time: R = 4 (fast mode, -v R=4): ~1 s; R = 10: ~2 min; R = 20
-- (-v jam_min_phi=0.0075): 66 min on one core, 12.6 M steps to its jam (7.4 h and 63.1 M
-- steps with Gear q = 6); slender -t 2 on two free cores: see docs/performance.md.
-- Thesis parameters: a = 1, Y = 1000, nu = 0.33, mu_s = 0.2, mu_d = 0.18; R in
-- {4, 5, 10, 13, 20, 40, 50}.
require("lib.scene").run { name = "low_torsion", R = 10, jam_time = 2.418,
  bend = function(sim, k) sim:bond("rod/straight", { YI = k.YI, node_energy = true }) end }

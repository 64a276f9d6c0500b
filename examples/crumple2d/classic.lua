-- Purpose: the thesis' classic crumpling scene (W2-1, MODELS.md §7.2): loop cascades
-- near the wall with two-fold symmetry, run until the wire jams.
-- Expected run time: f = 10 (fast mode, -v f=10): ~40 s; f = 100: many hours.
-- Thesis parameters: f = 100, kappa_theta = 0.04, mu_st = 5, s = 0.08 (feed speed).
require("lib.scene").run { name = "classic", f = 100, yield = 0.04, mu = 5.0, s = 0.08 }

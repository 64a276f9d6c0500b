-- Purpose: the thesis' classic crumpling scene (W2-1, MODELS.md §7.2): loop cascades
-- near the wall with two-fold symmetry, run until the wire jams.
-- Expected run time: f = 10 (fast mode, -v f=10): ~40 s; f = 100: 4.6 h on one core (73.7 M steps).
-- Thesis parameters: f = 100, kappa_theta = 0.04, mu_st = 5, s = 0.08 (feed speed).
-- At f = 100 this feed is too fast for the span to buckle as a whole: the wire folds at the
-- channels and jams at phi = 0.125 away from the wall (docs/crumple2d/timings.md); -v s=0.005
-- gives a centred first buckle at 16 times the steps. The folds come from the weak hardening
-- slope K_h = 0.05 K_e (MODELS.md §2.2 [C]; the thesis gives none): -v hardening=0.8 gives
-- large loops along the wall (docs/crumple2d/hardening_f25.md).
require("lib.scene").run { name = "classic", f = 100, yield = 0.04, mu = 5.0, s = 0.08 }

-- Purpose: the thesis' plastic scene (W2-3, docs/models.md §7.2): starts like the classic
-- one, then the symmetry breaks and loops rearrange; higher final packing density.
-- Expected run time (one core): f = 10 (fast mode, -v fast=1): ~1 s; f = 100 to phi = 0.14
-- (-v max_phi=0.14, W2-5): ~8 min (4.6 M steps); to the jam: longer, not yet measured under
-- the converged drag (the old drag, -v drag_factor=1, jammed at phi = 0.08 folded at the
-- channels after 2.7 M steps).
-- Thesis parameters: f = 100, kappa_theta = 0.02, mu_st = 5, s = 0.04 (feed speed).
require("lib.scene").run { name = "plastic", f = 100, yield = 0.02, mu = 5.0, s = 0.04 }

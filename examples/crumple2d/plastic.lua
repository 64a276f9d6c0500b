-- Purpose: the thesis' plastic scene (W2-3, docs/models.md §7.2): starts like the classic
-- one, then the symmetry breaks and loops rearrange; higher final packing density.
-- Expected run time: f = 10 (fast mode, -v fast=1): ~2 s; f = 25: ~40 s; f = 100: 5 min with -t 2
-- (2.7 M steps; it jams at phi = 0.08, folded at the channels).
-- Thesis parameters: f = 100, kappa_theta = 0.02, mu_st = 5, s = 0.04 (feed speed).
require("lib.scene").run { name = "plastic", f = 100, yield = 0.02, mu = 5.0, s = 0.04 }

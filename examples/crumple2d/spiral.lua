-- Purpose: the thesis' spiral scene (W2-2, docs/models.md §7.2): an elastic, frictionless
-- wire winds into two nested spirals round an S-shaped core and can fill the cavity.
-- Expected run time (one core): f = 10 (fast mode, -v fast=1): ~1 s; f = 25 to phi = 0.8: ~2 min
-- (1.4 M steps); f = 50 took 46 min with -t 2 under the old drag (-v drag_factor=1; 6.9 M
-- steps, phi = 0.94); f = 100: ~10 h with -t 2 (projected: steps and nodes both grow as f^2).
-- Thesis parameters: f = 100, kappa_theta = pi/2 (effectively elastic), mu_st = 0,
-- s = 0.04 (feed speed).
require("lib.scene").run { name = "spiral", f = 100, yield = math.pi / 2, mu = 0.0, s = 0.04 }

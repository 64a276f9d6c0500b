"""slender.crumple and slender.packing: the measures the study scripts use, on data with
known answers."""
import math

import numpy as np

from slender import crumple, packing


def test_power_law_recovers_exponent_and_prefactor(tmp_path):
    phi = np.linspace(0.05, 0.5, 40)
    path = tmp_path / "thermo.csv"
    with open(path, "w") as fh:
        fh.write("step,feed.phi,loops.loops\n")
        for i, p in enumerate(phi):
            fh.write(f"{i},{p},{3.0 * p ** 1.7}\n")
    rows = crumple.read([str(path)])
    fit = crumple.power_law(rows, "feed.phi", "loops.loops", 0.1, 0.4)
    assert abs(fit["exponent"] - 1.7) < 1e-9 and abs(fit["prefactor"] - 3.0) < 1e-9
    assert fit["n"] == sum(0.1 <= p <= 0.4 for p in phi) and fit["r2"] > 1 - 1e-12


def test_first_crossing_and_growth():
    phi = np.linspace(0.0, 0.1, 101)
    F = np.exp(phi / 0.002)  # grows tenfold over dphi = 0.002 ln 10 = 0.0046
    assert abs(crumple.first_crossing(phi, F, math.exp(10)) - 0.021) < 1e-12
    assert abs(crumple.first_growth(phi, F, 10.0, 0.005) - 0.005) < 1e-12
    assert math.isnan(crumple.first_growth(phi, F, 1e9, 0.005))


def test_lognormal_fit_of_a_lognormal_sample():
    rng = np.random.default_rng(1)
    x = rng.lognormal(mean=0.5, sigma=0.3, size=20000)
    mu, sigma, ks = packing.lognormal_fit(x)
    assert abs(mu - 0.5) < 0.01 and abs(sigma - 0.3) < 0.01 and ks < 0.02, (mu, sigma, ks)
    # a uniform sample is far from any log-normal
    assert packing.lognormal_fit(rng.uniform(1, 2, size=20000))[2] > 0.02

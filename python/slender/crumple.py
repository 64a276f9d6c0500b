"""Measures of 2D crumpling runs (docs/models.md §2.7, §2.8): thermo CSVs read into rows,
power-law fits with standard errors, the analytic spiral model's bending energy, and where
an injection force first crosses a threshold or grows by a factor. Used by
scripts/crumple_stats.py and the validation report; importable by users:

    from slender import crumple
    rows = crumple.read(["classic_thermo.csv"])
    fit = crumple.power_law(rows, "feed.phi", "loops.loops", 0.1, 0.4)
"""
import csv
import math

import numpy as np


def read(paths):
    rows = []
    for p in paths:
        with open(p) as fh:
            for r in csv.DictReader(fh):
                rows.append({k: float(v) for k, v in r.items() if v not in ("", None)})
    return rows


def linfit(x, y):
    """Least squares y = a + b x; returns b, a, stderr(b), r^2."""
    x, y = np.asarray(x), np.asarray(y)
    A = np.vstack([np.ones_like(x), x]).T
    coef, res, *_ = np.linalg.lstsq(A, y, rcond=None)
    a, b = coef
    resid = y - (a + b * x)
    n = len(x)
    s2 = resid @ resid / max(n - 2, 1)
    sb = math.sqrt(s2 / max(((x - x.mean()) ** 2).sum(), 1e-300))
    ss = ((y - y.mean()) ** 2).sum()
    return b, a, sb, 1 - (resid @ resid) / ss if ss > 0 else 1.0


def power_law(rows, xkey, ykey, lo, hi):
    pts = [(r[xkey], r[ykey]) for r in rows
           if r.get(ykey, 0) > 0 and lo <= r.get(xkey, 0) <= hi]
    if len(pts) < 3:
        return None
    x, y = zip(*pts)
    b, a, sb, r2 = linfit(np.log(x), np.log(y))
    return {"exponent": b, "stderr": sb, "prefactor": math.exp(a), "r2": r2, "n": len(pts),
            "x": np.array(x), "y": np.array(y)}


def spiral_model(phi, R, d, YI, printed):
    """Bending energy of the spiral model (docs/models.md §2.8) up to the constant C."""
    Rc = 0.5 * (d + np.sqrt(d * d + 4 * R * R * (1 - phi)))            # (3.4)
    core = 4 * math.pi * YI / Rc                                        # E_c as printed
    if printed:
        phimax = math.pi * (R - Rc) / d                                 # (3.7)
        Es = YI / d * (np.log(d * phimax + math.pi * Rc) - np.log(math.pi * Rc))  # (3.10)
    else:
        Es = math.pi * YI / (2 * d) * np.log(R / Rc)                    # corrected
    return core + 2 * Es


def read_run(spec):
    """One run's thermo rows from 'a.csv+b.csv', ordered by step, repeated steps once."""
    by_step = {}
    for r in read(spec.split("+")):
        by_step[r["step"]] = r
    return [by_step[k] for k in sorted(by_step)]


def first_crossing(phi, F, level):
    i = np.nonzero(F > level)[0]
    return phi[i[0]] if len(i) else float("nan")


def first_growth(phi, F, factor, dphi):
    """First phi where F exceeds factor times its value at phi - dphi (docs/models.md §2.4)."""
    for i in range(len(phi)):
        j = np.searchsorted(phi, phi[i] - dphi)
        if phi[i] - phi[j] <= dphi and F[j] > 0 and F[i] > factor * F[j]:
            return phi[i]
    return float("nan")

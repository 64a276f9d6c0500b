#!/usr/bin/env python3
"""Checks the inverse-spool (Purohit) model of scripts/pack3d_stats.py against the
constants of docs/models.md §5.4 / §7.1 (A-4) and its limits, and the log-normal fit."""
import math
import os
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import pack3d_stats  # noqa: E402


def spool(ds, R, edges_of_hoop):
    """Hoops round the z axis on a hexagonal lattice of spacing ds in (r, z) (the inverse
    spool) inside a sphere of radius R; edges_of_hoop(r) edges per hoop."""
    pos, edges = [], []
    for i in range(12):
        for j in range(-12, 13):
            r = 1.5 + i * math.sqrt(3) / 2 * ds
            z = (j + 0.5 * (i % 2)) * ds
            if r * r + z * z > (R - 0.5) ** 2:
                continue
            first, m = len(pos), edges_of_hoop(r)
            ang = np.linspace(0, 2 * np.pi, m, endpoint=False)
            pos.extend(np.stack([r * np.cos(ang), r * np.sin(ang), np.full_like(ang, z)], axis=1))
            edges.extend((first + q, first + (q + 1) % m) for q in range(m))
    return np.array(pos), np.array(edges)


def main():
    phi = np.array([1e-6, 0.2, 0.4, 0.45940, 0.46])
    k, eb, f, rg2 = pack3d_stats.purohit(phi, R=10.0, ds=2.81)
    assert abs(k - 1.6796) < 1e-4, k
    assert abs(k ** -1.5 - 0.4594) < 1e-4                   # the model's end
    assert abs(f[0] - 0.5) < 1e-3 and abs(rg2[0] - 1) < 1e-3  # empty sphere
    assert np.isnan(eb[-1]) and np.isnan(f[-1])              # past the end
    assert abs(rg2[3] - 0.6) < 1e-3                         # full: the solid-sphere 3/5
    assert eb[1] < eb[2] and f[1] < f[2]
    # E_b = 4 pi YI R / (sqrt 3 d_s^2) (artanh x - x): E_b R / YI at phi = 0.2, R = 10
    x = math.sqrt(k) * 0.2 ** (1 / 3)
    assert abs(eb[1] - 4 * math.pi * 100 / (math.sqrt(3) * 2.81 ** 2) * (math.atanh(x) - x)) < 1e-9
    # log-normal fit recovers mu and sigma of a sample
    rng = np.random.default_rng(1)
    mu, sigma, ks = pack3d_stats.lognormal_fit(np.exp(rng.normal(-0.3, 0.8, 20000)))
    assert abs(mu + 0.3) < 0.02 and abs(sigma - 0.8) < 0.02 and ks < 0.02, (mu, sigma, ks)
    # strand spacing from cross-sections: hoops round the z axis on a hexagonal lattice
    # of spacing d_s in (r, z) (the inverse spool) give nearest sections d_s apart
    ds, R = 2.81, 30.0
    pos, edges = spool(ds, R, lambda r: 600)
    nn, six = pack3d_stats.strand_spacing(pos, edges, R=R, planes=3, margin=3.0)
    assert len(nn) > 300 and abs(np.median(nn) - ds) < 0.01, (len(nn), np.median(nn))
    assert abs(np.median(six) - ds) < 0.01, np.median(six)
    # order of the spool: parallel neighbouring hoops, all round the axis, and an empty
    # column (the innermost hoop has r = 1.5, the column reaches R / 4 = 7.5, so a few
    # hoops lie in it); an isotropic tangle of the same size: no order, no empty column
    # (rebuilt with edges of about a, as in the packings)
    pos, edges = spool(ds, R, lambda r: max(12, round(2 * math.pi * r)))
    lattice = pack3d_stats.packing_order(pos, edges, R=R)
    assert lattice["local_order"] > 0.98 and lattice["hoop_alignment"] > 0.999, lattice
    rng = np.random.default_rng(2)
    n = 20000
    mid = rng.normal(size=(n, 3))
    mid *= (R * rng.random(n) ** (1 / 3) / np.linalg.norm(mid, axis=1))[:, None]
    tan = rng.normal(size=(n, 3))
    tan /= np.linalg.norm(tan, axis=1)[:, None]
    tangle = np.concatenate([mid - 0.5 * tan, mid + 0.5 * tan])
    tangle_edges = np.stack([np.arange(n), np.arange(n, 2 * n)], axis=1)
    iso = pack3d_stats.packing_order(tangle, tangle_edges, R=R)
    assert abs(iso["local_order"]) < 0.03 and iso["order_pairs"] > 1000, iso
    assert abs(iso["hoop_alignment"] - 0.5) < 0.01, iso
    assert abs(iso["column_density"] - 1.0) < 0.05, iso
    # a spool whose hoops all lie outside r = 8 leaves the column empty
    outer = [k for k, e in enumerate(edges) if math.hypot(*pos[e[0]][:2]) > 8.0]
    ring = pack3d_stats.packing_order(pos, edges[outer], R=R)
    assert ring["column_density"] == 0.0 and ring["local_order"] > 0.99, ring
    print("pack3d scripts: ok")


if __name__ == "__main__":
    main()

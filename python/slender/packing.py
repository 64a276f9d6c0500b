"""Measures of 3D packings (docs/models.md §5, §7.3): the inverse-spool (Purohit) energy,
a log-normal fit, the spacing of strands across planes through the sphere, pairs of
nodes closer than a cutoff, and the local order of a packing. Used by
scripts/pack3d_stats.py and the validation report; importable by users:

    from slender import packing
    order = packing.packing_order(positions, edges, R)
"""
import math

import numpy as np


def purohit(phi, R, ds=2.81, a=1.0):
    """E_b R / YI, F R^2 / YI, R_g^2 / R^2 of the inverse-spool model; nan past its end.
    d_s in units of a; E_b = 4 pi YI R / (sqrt 3 d_s^2) (artanh x - x)."""
    k = (3 * ds ** 4 / (4 * math.pi ** 2 * a ** 4)) ** (1 / 3)
    x = np.sqrt(k) * np.cbrt(phi)
    with np.errstate(invalid="ignore", divide="ignore"):
        eb = 4 * math.pi * R ** 2 / (math.sqrt(3) * (ds * a) ** 2) * (np.arctanh(x) - x)
        f = 1 / (2 * (1 - k * phi ** (2 / 3)))
        rg2 = 1 - 0.4 * k * phi ** (2 / 3)
    bad = x >= 1
    for arr in (eb, f, rg2):
        arr[bad] = np.nan
    return k, eb, f, rg2


def lognormal_fit(x):
    lx = np.log(x)
    mu, sigma = float(lx.mean()), float(lx.std(ddof=1))
    # KS distance between the empirical CDF and the fitted log-normal CDF
    xs = np.sort(lx)
    emp = np.arange(1, len(xs) + 1) / len(xs)
    cdf = 0.5 * (1 + np.array([math.erf((v - mu) / (sigma * math.sqrt(2))) for v in xs]))
    ks = float(np.max(np.maximum(np.abs(emp - cdf), np.abs(emp - 1 / len(xs) - cdf))))
    return mu, sigma, ks


def strand_spacing(pos, edges, R, planes=12, exclude=3, margin=3.0):
    """Distances between the sections of the rod in `planes` planes through the z axis
    (the feed axis), inside the sphere of radius R. Sections of edges fewer than
    `exclude` apart along the chain are not neighbours (a strand lying in the plane
    crosses it several times in a row). Returns, for the sections more than `margin`
    from the sphere, the distance to the nearest other section and the mean distance
    to the six nearest: both are d_s in the hexagonal packing of the inverse spool;
    in a real packing the first is the contact distance of the closest pair and the
    second also sees the gaps around a strand."""
    pos = np.asarray(pos, float)
    edges = np.asarray(edges, int)
    xa, xb = pos[edges[:, 0]], pos[edges[:, 1]]
    inside = (np.linalg.norm(xa, axis=1) < R) & (np.linalg.norm(xb, axis=1) < R)
    index = np.arange(len(edges))
    nearest, six = [], []
    for th in np.pi * np.arange(planes) / planes:
        n = np.array([np.cos(th), np.sin(th), 0.0])
        u = np.array([-np.sin(th), np.cos(th), 0.0])
        sa, sb = xa @ n, xb @ n
        cut = inside & (sa * sb < 0)
        if cut.sum() < 7:
            continue
        t = sa[cut] / (sa[cut] - sb[cut])
        p = xa[cut] + t[:, None] * (xb[cut] - xa[cut])
        pts = np.stack([p @ u, p[:, 2]], axis=1)
        k = index[cut]
        d = np.linalg.norm(pts[:, None, :] - pts[None, :, :], axis=2)
        d[np.abs(k[:, None] - k[None, :]) < exclude] = np.inf
        d.sort(axis=1)
        deep = np.linalg.norm(pts, axis=1) < R - margin
        ok = deep & np.isfinite(d[:, 5])
        nearest.extend(d[ok, 0])
        six.extend(d[ok, :6].mean(axis=1))
    return np.array(nearest), np.array(six)


def near_pairs(p, cutoff):
    """Index pairs (i < j) of points closer than `cutoff`, by a cell list of that size."""
    p = np.asarray(p, float)
    cell = np.floor(p / cutoff).astype(np.int64)
    keys, inverse = np.unique(cell, axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    order = np.argsort(inverse, kind="stable")
    start = np.searchsorted(inverse[order], np.arange(len(keys) + 1))
    where = {tuple(k): c for c, k in enumerate(keys)}
    offsets = [(i, j, k) for i in (-1, 0, 1) for j in (-1, 0, 1) for k in (-1, 0, 1)]
    out_i, out_j = [], []
    for c, key in enumerate(keys):
        mine = order[start[c]:start[c + 1]]
        for off in offsets:
            o = where.get((key[0] + off[0], key[1] + off[1], key[2] + off[2]))
            if o is None or o < c:
                continue
            other = order[start[o]:start[o + 1]]
            d = np.linalg.norm(p[mine][:, None, :] - p[other][None, :, :], axis=2)
            i, j = np.nonzero(d < cutoff)
            i, j = mine[i], other[j]
            keep = i < j if o == c else np.ones(len(i), bool)
            out_i.append(np.minimum(i, j)[keep])
            out_j.append(np.maximum(i, j)[keep])
    if not out_i:
        return np.zeros(0, int), np.zeros(0, int)
    return np.concatenate(out_i), np.concatenate(out_j)


def packing_order(pos, edges, R, a=1.0, cutoff=3.0, exclude=4, column=0.25):
    """How ordered a packing is (docs/models.md §7.2 W3-1 against W3-2: onion-like shells
    round an empty column along the feed axis z, against a disordered homogeneous
    filling). For the edges inside the sphere:
    - local_order: the mean of P2(t_i . t_j) = (3 (t_i . t_j)^2 - 1) / 2 over pairs of
      edges whose midpoints are closer than `cutoff` a and that are more than `exclude`
      edges apart along the rod (other strands, not the same one): 1 for parallel
      neighbouring strands (a spool), 0 for an isotropic tangle;
    - hoop_alignment: the length-weighted mean of |t . e_phi|, e_phi the azimuthal
      direction round the feed axis (edges more than a from the axis): 1 for hoops
      round the axis, 1/2 for isotropic directions;
    - column_density: the rod length within `column` R of the feed axis over what an
      even filling of the sphere would put there: 0 for an empty column, 1 for even."""
    pos = np.asarray(pos, float)
    edges = np.asarray(edges, int)
    edges = edges[edges[:, 0] != edges[:, 1]]  # a dump pads the frames of a growing rod with (0, 0)
    xa, xb = pos[edges[:, 0]], pos[edges[:, 1]]
    inside = (np.linalg.norm(xa, axis=1) < R) & (np.linalg.norm(xb, axis=1) < R)
    xa, xb, index = xa[inside], xb[inside], np.arange(len(edges))[inside]
    seg = xb - xa
    length = np.linalg.norm(seg, axis=1)
    t = seg / np.maximum(length, 1e-300)[:, None]
    mid = 0.5 * (xa + xb)
    i, j = near_pairs(mid, cutoff * a)
    far = np.abs(index[i] - index[j]) > exclude
    i, j = i[far], j[far]
    c = np.sum(t[i] * t[j], axis=1)
    rho = np.hypot(mid[:, 0], mid[:, 1])
    off_axis = rho > a
    ephi = np.stack([-mid[:, 1], mid[:, 0], np.zeros(len(mid))], axis=1) / np.maximum(rho, 1e-300)[:, None]
    hoop = np.abs(np.sum(t * ephi, axis=1))
    rc = column * R
    share = 1.0 - (1.0 - (rc / R) ** 2) ** 1.5  # volume of the column inside the sphere / sphere
    in_column = length[rho < rc].sum() / max(length.sum(), 1e-300)
    return {"local_order": float(np.mean(1.5 * c * c - 0.5)) if len(c) else float("nan"),
            "order_pairs": int(len(c)),
            "hoop_alignment": float(np.sum(hoop[off_axis] * length[off_axis]) /
                                    max(length[off_axis].sum(), 1e-300)),
            "column_density": float(in_column / share)}

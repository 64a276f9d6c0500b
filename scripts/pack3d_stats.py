#!/usr/bin/env python3
"""Analysis of a 3D packing run (examples/pack3d; docs/models.md §5.4):

- E_b R / YI and F R^2 / YI against phi, with the inverse-spool (Purohit) model
  (4.50)-(4.60) for the strand spacing d_s (default 2.81 a: k = 1.6796, the model
  ends at phi = 0.4594), with the hoop energy prefactor pi of docs/models.md §5.4 [R];
- R_g / R against phi with the model's R_g^2 / R^2 = 1 - 2/5 k phi^(2/3);
- the distribution of the per-node bending energy x = E_i / <E> in the last frame
  of the trajectory (nodes inside the sphere, logarithmic bins) with a log-normal fit
  (4.49) by maximum likelihood (mu = mean ln x, sigma = std ln x), and the
  Kolmogorov-Smirnov distance of the fit;
- the strand spacing d_s measured from cross-sections (docs/models.md §7.2 W3-5): the
  rod cut by planes through the feed axis (z), and in each plane the distance from
  every strand's section to its nearest other section and the mean distance to its six
  nearest; in the hexagonal packing of the inverse-spool model both are d_s (the
  thesis measured 2.81 a);
- how ordered the last frame is (W3-1 against W3-2): the local nematic order of
  neighbouring strands, the alignment of the rod with hoops round the feed axis, and
  the density in a column round that axis against an even filling (packing_order).

  /usr/bin/python3 scripts/pack3d_stats.py low_torsion_thermo.csv low_torsion.h5 --R 10 --out docs/pack3d/low_torsion_R10
  (a restarted run: list its dumps in order, low_torsion.h5 low_torsion_<time>.h5)
"""
import argparse
import csv
import json
import math
import os

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


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("thermo")
    ap.add_argument("trajectory", nargs="*",
                    help="H5MD dumps with bend.energy, in order (a restarted run writes a new one): the "
                         "last frame gives the distribution and the spacing, every frame the order")
    ap.add_argument("--R", type=float, required=True, help="sphere radius")
    ap.add_argument("--a", type=float, default=1.0)
    ap.add_argument("--YI", type=float, default=math.pi * 1000 / 4)
    ap.add_argument("--ds", type=float, default=2.81, help="Purohit strand spacing d_s")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)

    with open(a.thermo) as fh:
        rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(fh)]
    rows = [r for r in rows if r["feed.phi"] > 0]
    phi = np.array([r["feed.phi"] for r in rows])
    eb = np.array([r["energy.bend"] for r in rows]) * a.R / a.YI
    F = np.array([r["feed.force_avg"] for r in rows]) * a.R ** 2 / a.YI
    rg = np.array([r.get("gyr.rg", np.nan) for r in rows]) / a.R
    k, meb, mf, mrg2 = purohit(phi, a.R, a.ds, a.a)
    summary = {"R": a.R, "phi_max": float(phi.max()), "purohit_k": k, "purohit_phi_end": k ** -1.5,
               "final_bend_R_over_YI": float(eb[-1]), "final_force_R2_over_YI": float(F[-1])}

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(13, 4))
    ax[0].plot(phi, eb, ".", ms=3, label="simulation")
    ax[0].plot(phi, meb, "-", label=f"Purohit, d_s = {a.ds:g} a")
    ax[0].set_ylabel("E_b R / YI")
    ax[1].semilogy(phi, np.maximum(F, 1e-6), ".", ms=3, label="simulation (1000-step average)")
    ax[1].semilogy(phi, mf, "-", label="Purohit")
    ax[1].set_ylabel("F R^2 / YI")
    ax[2].plot(phi, rg, ".", ms=3, label="simulation")
    ax[2].plot(phi, np.sqrt(mrg2), "-", label="Purohit")
    ax[2].set_ylabel("R_g / R")
    for x in ax:
        x.set_xlabel("packing fraction phi")
        x.legend(fontsize=8)
    fig.suptitle(f"3D packing, R = {a.R:g} a", fontsize=10)
    fig.tight_layout()
    fig.savefig(a.out + "_vs_phi.png", dpi=110)
    plt.close(fig)

    if a.trajectory:
        import h5py

        def frame(h, k):
            pos = h["particles/all/position/value"][k]
            edges = (h["connectivity/edges/value"][k] if "connectivity/edges" in h
                     else np.stack([np.arange(len(pos) - 1), np.arange(1, len(pos))], axis=1))
            return pos, edges

        # order against phi over every dumped frame (phi from the thermo rows by step)
        steps = np.array([r["step"] for r in rows])
        curve = []
        for name in a.trajectory:
            with h5py.File(name, "r") as h:
                for k, st in enumerate(h["particles/all/position/step"][:]):
                    if steps.size and steps[0] <= st <= steps[-1]:
                        o = packing_order(*frame(h, k), a.R, a.a)
                        curve.append((float(np.interp(st, steps, phi)), o["local_order"],
                                      o["hoop_alignment"], o["column_density"]))
        with h5py.File(a.trajectory[-1], "r") as h:
            pos, edges = frame(h, -1)
            e = np.asarray(h["particles/all/bend.energy/value"][-1]).reshape(-1)
        if curve:
            c = np.array(sorted(curve))
            fig, ax = plt.subplots(figsize=(5, 4))
            ax.plot(c[:, 0], c[:, 1], ".-", ms=3, label="local order <P2(t_i . t_j)>")
            ax.plot(c[:, 0], c[:, 2], ".-", ms=3, label="hoop alignment <|t . e_phi|>")
            ax.plot(c[:, 0], c[:, 3], ".-", ms=3, label="column density (r < R/4) / even")
            ax.axhline(0.5, color="0.6", ls=":", lw=0.8)
            ax.set_xlabel("packing fraction phi")
            ax.set_ylim(0, 1.3)
            ax.legend(fontsize=7)
            ax.set_title(f"order of the packing, R = {a.R:g} a (isotropic: 0, 1/2, 1)", fontsize=9)
            fig.tight_layout()
            fig.savefig(a.out + "_order.png", dpi=110)
            plt.close(fig)
        nn, six = strand_spacing(pos, edges, a.R, margin=3 * a.a)
        nn, six = nn / a.a, six / a.a
        if len(nn):
            summary.update({"strand_nearest_median_over_a": float(np.median(nn)),
                            "strand_six_nearest_median_over_a": float(np.median(six)),
                            "strand_sections": int(len(nn))})
            fig, ax = plt.subplots(figsize=(5, 4))
            bins = np.linspace(0, max(6.0, np.percentile(six, 99)), 40)
            ax.hist(nn, bins=bins, histtype="step", label=f"nearest: median {np.median(nn):.2f} a")
            ax.hist(six, bins=bins, histtype="step", label=f"six nearest (mean): median {np.median(six):.2f} a")
            ax.axvline(2.81, color="r", ls=":", label="thesis d_s = 2.81 a")
            ax.axvline(2.0, color="0.5", ls="--", label="touching, 2 a")
            ax.set_xlabel("distance between strand sections / a")
            ax.set_ylabel(f"sections ({len(nn)} in 12 planes through the feed axis)")
            ax.legend(fontsize=7)
            fig.tight_layout()
            fig.savefig(a.out + "_strand_spacing.png", dpi=110)
            plt.close(fig)
        summary.update(packing_order(pos, edges, a.R, a.a))
        inside = np.linalg.norm(pos, axis=1) < a.R
        e = e[inside & (e > 0)]
        x = e / e.mean()
        mu, sigma, ks = lognormal_fit(x)
        summary.update({"lognormal_mu": mu, "lognormal_sigma": sigma, "lognormal_ks": ks, "nodes": int(len(x))})
        bins = np.logspace(np.log10(x.min()), np.log10(x.max()), 25)
        hist, edges = np.histogram(x, bins=bins, density=True)
        centres = np.sqrt(edges[1:] * edges[:-1])
        fig, ax = plt.subplots(figsize=(5, 4))
        ax.loglog(centres[hist > 0], hist[hist > 0], "o", ms=4, label=f"{len(x)} nodes")
        xs = np.logspace(np.log10(x.min()), np.log10(x.max()), 200)
        ax.loglog(xs, np.exp(-(np.log(xs) - mu) ** 2 / (2 * sigma ** 2)) / (sigma * xs * math.sqrt(2 * math.pi)),
                  "-", label=f"log-normal mu = {mu:.2f}, sigma = {sigma:.2f}, KS = {ks:.3f}")
        ax.set_xlabel("x = E_b[i] / <E_b>")
        ax.set_ylabel("p(x)")
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(a.out + "_energy_distribution.png", dpi=110)
        plt.close(fig)
    with open(a.out + ".json", "w") as fh:
        json.dump(summary, fh, indent=1)
    print(json.dumps(summary, indent=1))
    print("wrote", a.out + "_vs_phi.png", a.out + ".json")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Analysis of a 3D packing run (examples/pack3d; MODELS.md §5.4):

- E_b R / YI and F R^2 / YI against phi, with the inverse-spool (Purohit) model
  (4.50)-(4.60) for the strand spacing d_s (default 2.81 a: k = 1.6796, the model
  ends at phi = 0.4594), with the hoop energy prefactor pi of MODELS.md [R];
- R_g / R against phi with the model's R_g^2 / R^2 = 1 - 2/5 k phi^(2/3);
- the distribution of the per-node bending energy x = E_i / <E> in the last frame
  of the trajectory (nodes inside the sphere, logarithmic bins) with a log-normal fit
  (4.49) by maximum likelihood (mu = mean ln x, sigma = std ln x), and the
  Kolmogorov-Smirnov distance of the fit;
- the strand spacing d_s measured from cross-sections (MODELS.md §7.2 W3-5): the
  rod cut by planes through the feed axis (z), and in each plane the distance from
  every strand's section to its nearest other section and the mean distance to its six
  nearest; in the hexagonal packing of the inverse-spool model both are d_s (the
  thesis measured 2.81 a).

  /usr/bin/python3 scripts/pack3d_stats.py low_torsion_thermo.csv low_torsion.h5 --R 10 --out docs/pack3d/low_torsion_R10
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


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("thermo")
    ap.add_argument("trajectory", nargs="?", help="H5MD dump with bend.energy (for the distribution)")
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
        with h5py.File(a.trajectory, "r") as h:
            pos = h["particles/all/position/value"][-1]
            e = np.asarray(h["particles/all/bend.energy/value"][-1]).reshape(-1)
            edges = (h["connectivity/edges/value"][-1] if "connectivity/edges" in h
                     else np.stack([np.arange(len(pos) - 1), np.arange(1, len(pos))], axis=1))
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

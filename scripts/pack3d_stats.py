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
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))
# the measures live in the package; the names stay importable from here
from slender.packing import (lognormal_fit, near_pairs, packing_order, purohit,  # noqa: E402,F401
                             strand_spacing)


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

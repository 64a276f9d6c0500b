#!/usr/bin/python3
"""Plots for the shell examples (examples/shells).

  shell_plots.py render SURFACE.h5 OUT.png [--field koiter.Ub] [--frame -1]
      the limit surface of a frame written by dump "shell", faces coloured by a
      per-face field (log scale for U_b), seen from two directions
  shell_plots.py econe ECONE.csv OUT.png [--kiss PHI]
      E_b_hat, E_s/E_b and the contact-plane angle gamma against phi_e, with the
      first self-contact marked
  shell_plots.py sphere SPHERE.csv [OTHER.csv] OUT.png
      bending and stretching energy against the confinement f = D / R_s, for one
      run or for the shrinking sphere and growth in a fixed sphere together
  shell_plots.py sphere-maps SHRINK.h5 GROW.h5 OUT.png [--frame -1]
      the U_b maps of the shrinking sphere (S-6) and growth in a fixed sphere (S-7)
      at the same frame (the decks write one per sample, at equal f): both shapes on
      one colour scale, the area-weighted distribution of U_b, and how much of E_b
      sits in the most strained tenth of the area (printed too)
  shell_plots.py branches BRANCHES.csv OUT.png [--extra LABEL=ECONE.csv ...]
      the S-2 stability run (econe_stability.lua): E_b_hat and gamma against phi_e
      on the symmetric branch held by friction, the skewed branch, and the release
      tests; --extra overlays e-cone ramps (econe.lua logs), e.g. the companion
      runs without contact and from the n = 3 mode
"""
import argparse
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))
from slender import plot  # noqa: E402  (selects the Agg backend)
from slender.io import Surface  # noqa: E402

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read_csv(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"{path}: no rows")
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def render(args):
    plot.render_surface(args.surface, args.out, args.frame, field=args.field)
    print(f"wrote {args.out}")


def econe(args):
    d = read_csv(args.csv)
    phi = d["phi_e"]
    fig, axes = plt.subplots(1, 3, figsize=(13, 4))
    axes[0].plot(phi, d["Eb_hat"], "o-")
    axes[0].set_ylabel(r"$\hat E_b$")
    # the flat disc before it buckles has E_b ~ 0: leave those ratios out
    bent = d["Eb_hat"] > 1e-3 * max(d["Eb_hat"].max(), 1e-300)
    axes[1].plot(phi[bent], d["E_s"][bent] / d["E_b"][bent], "o-", label="$E_s / E_b$")
    axes[1].set_ylabel(r"$E_s / E_b$")
    if "R_C" in d and (d["R_C"] > 0).any():
        # the core radius of compute core_radius, on a second axis
        ax = axes[1].twinx()
        okr = bent & (d["R_C"] > 0)
        ax.plot(phi[okr], d["R_C"][okr], "s--", color="tab:red", label="$R_C$")
        ax.set_ylabel(r"core radius $R_C / R$", color="tab:red")
    ok = d["gamma"] >= 0
    axes[2].plot(phi[ok], np.degrees(d["gamma"][ok]), "o-")
    axes[2].set_ylabel(r"contact-plane angle $\gamma$ (deg)")
    # first contact of the wings: the deck's bisected angle (--kiss), else the first
    # logged state with wing contacts (far_contacts), or with any contact in older files
    touch = np.nonzero(d.get("far_contacts", d["contacts"]) > 0)[0]
    kiss = args.kiss if args.kiss is not None else (phi[touch[0]] if len(touch) else None)
    for ax in axes:
        ax.set_xlabel(r"excess angle $\phi_e$")
        if kiss is not None:
            ax.axvline(kiss, color="r", ls=":", label=f"first contact ({kiss:.3f})")
    if kiss is not None:
        axes[0].legend()
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)
    print(f"wrote {args.out}")


def sphere(args):
    *csvs, out = args.files
    if not csvs:
        sys.exit("sphere: give one or two CSV files and the output PNG")
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for path in csvs:
        d = read_csv(path)
        label = ("shrinking sphere (S-6)" if "shrink" in path else
                 "growth in a fixed sphere (S-7)" if "grow" in path else path)
        axes[0].plot(d["f"], d["E_b"], "o-", label=label)
        axes[1].plot(d["f"], d["E_s"], "o-", label=label)
    axes[0].set_ylabel("bending energy")
    axes[1].set_ylabel("stretching energy")
    for ax in axes:
        ax.set_xlabel(r"confinement $f = D / R_s$")
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")


def read_map(path, frame):
    with Surface(path) as s:
        pos, tri = s.mesh(frame)
        time = float(s.times[frame])
        ub = s.face_field("koiter.Ub", frame)
    p = pos[tri]
    area = 0.5 * np.linalg.norm(np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), axis=1)
    return tri, pos, time, ub, area


def concentration(ub, area, top=0.1):
    """Share of the bending energy in the `top` fraction of the area with the highest U_b."""
    order = np.argsort(-ub)
    a, e = np.cumsum(area[order]), np.cumsum((ub * area)[order])
    return float(np.interp(top * a[-1], a, e) / e[-1])


def sphere_maps(args):
    runs = [("shrinking sphere (S-6)", *read_map(args.shrink, args.frame)),
            ("growth in a fixed sphere (S-7)", *read_map(args.grow, args.frame))]
    logs = [np.log10(np.maximum(r[4], 1e-12)) for r in runs]
    both = np.concatenate(logs)
    norm = plt.Normalize(np.percentile(both, 2), np.percentile(both, 98))
    fig = plt.figure(figsize=(13, 8))
    for k, (label, tri, pos, time, ub, area) in enumerate(runs):
        for j, (elev, azim) in enumerate([(30, -60), (90, -90)]):
            ax = fig.add_subplot(2, 3, 3 * k + j + 1, projection="3d")
            plot.surface(ax, pos, tri, plt.cm.viridis(norm(logs[k])))
            ax.view_init(elev=elev, azim=azim)
            if j == 0:
                ax.set_title(f"{label}, t = {time:.3g}", fontsize=9)
    ax = fig.add_subplot(2, 3, 3)
    lines = []
    for (label, tri, pos, time, ub, area), lg in zip(runs, logs):
        ub_int = float((ub * area).sum())
        share = concentration(ub, area)
        ax.hist(lg, bins=40, weights=area / area.sum(), histtype="step", label=label)
        lines.append(f"{label}: integral of U_b over the area = {ub_int:.4g}, share of E_b in the top 10 % of area = {share:.2f}")
    ax.set_xlabel(r"$\log_{10} U_b$ per face")
    ax.set_ylabel("area fraction")
    ax.legend(fontsize=7)
    ax = fig.add_subplot(2, 3, 6)
    for label, tri, pos, time, ub, area in runs:
        order = np.argsort(-ub)
        ax.plot(np.cumsum(area[order]) / area.sum(), np.cumsum((ub * area)[order]) / (ub * area).sum(),
                label=label)
    ax.plot([0, 1], [0, 1], "k:", lw=0.8, label="uniform")
    ax.set_xlabel("area fraction, most strained first")
    ax.set_ylabel("share of bending energy")
    ax.legend(fontsize=7)
    sm = plt.cm.ScalarMappable(norm=norm, cmap="viridis")
    fig.colorbar(sm, ax=fig.axes[:4], shrink=0.5, label=r"$\log_{10} U_b$")
    fig.savefig(args.out, dpi=110)
    for line in lines:
        print(line)
    print(f"wrote {args.out}")


def branches(args):
    with open(args.csv) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"{args.csv}: no rows")
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    styles = {"symmetric": ("o-", "symmetric (static friction)"),
              "released": ("*", "released at the top"),
              "skewed": ("s-", "skewed (frictionless)"),
              "release_test": ("x", "release tests")}
    for branch, (style, label) in styles.items():
        sel = [r for r in rows if r["branch"] == branch]
        if not sel:
            continue
        phi = np.array([float(r["phi_e"]) for r in sel])
        eb = np.array([float(r["Eb_hat"]) for r in sel])
        gam = np.array([float(r["gamma"]) for r in sel])
        axes[0].plot(phi, eb, style, ms=5, label=label)
        ok = gam >= 0
        axes[1].plot(phi[ok], np.degrees(gam[ok]), style, ms=5, label=label)
    for extra in args.extra or []:
        label, _, path = extra.partition("=")
        d = read_csv(path)
        axes[0].plot(d["phi_e"], d["Eb_hat"], "--", lw=1.2, label=label)
        ok = d["gamma"] >= 0
        if ok.any():
            axes[1].plot(d["phi_e"][ok], np.degrees(d["gamma"][ok]), "--", lw=1.2, label=label)
    axes[0].set_ylabel(r"$\hat E_b$")
    axes[1].set_ylabel(r"contact-plane angle $\gamma$ (deg)")
    for ax in axes:
        ax.set_xlabel(r"excess angle $\phi_e$")
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)
    print(f"wrote {args.out}")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("render")
    r.add_argument("surface")
    r.add_argument("out")
    r.add_argument("--field", default="koiter.Ub")
    r.add_argument("--frame", type=int, default=-1)
    e = sub.add_parser("econe")
    e.add_argument("csv")
    e.add_argument("out")
    e.add_argument("--kiss", type=float, help="first-contact angle to mark (the deck's bisection)")
    s = sub.add_parser("sphere")
    s.add_argument("files", nargs="+", help="one or two CSV files, then the output PNG")
    m = sub.add_parser("sphere-maps")
    m.add_argument("shrink")
    m.add_argument("grow")
    m.add_argument("out")
    m.add_argument("--frame", type=int, default=-1)
    b = sub.add_parser("branches")
    b.add_argument("csv")
    b.add_argument("out")
    b.add_argument("--extra", action="append", help="LABEL=econe.csv: an e-cone ramp to overlay")
    args = p.parse_args()
    {"render": render, "econe": econe, "sphere": sphere, "sphere-maps": sphere_maps,
     "branches": branches}[args.cmd](args)


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Render a 3D packing frame (slender h5md dump of examples/pack3d) as a PNG: the rod
as a thick line in 3D coloured by the per-node bending energy (bend.energy, if
dumped), and a cut through the middle of the sphere: the rod's cross-sections
within a slab |z - z0| < a drawn as discs of radius a. Only the rod inside the sphere
(within R + 2a of its centre) is drawn, in chain order (slender.io).

  /usr/bin/python3 scripts/render_pack3d.py low_torsion.h5 --R 10 [--frame -1] [--out packing.png]
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))
from slender import plot  # noqa: E402  (selects the Agg backend)
from slender.io import Trajectory  # noqa: E402

import matplotlib.pyplot as plt  # noqa: E402


def inside_runs(chains, values, limit):
    """The stretches of each chain whose nodes lie within `limit` of the origin (at least
    two nodes: one segment), with their values."""
    runs, run_values = [], []
    for k, points in enumerate(chains):
        inside = np.linalg.norm(points, axis=1) < limit
        starts = np.flatnonzero(np.diff(np.r_[0, inside.astype(int)]) == 1)
        ends = np.flatnonzero(np.diff(np.r_[inside.astype(int), 0]) == -1) + 1
        for s, e in zip(starts, ends):
            if e - s >= 2:
                runs.append(points[s:e])
                run_values.append(values[k][s:e] if values is not None else np.zeros(e - s))
    return runs, run_values


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("file")
    ap.add_argument("--R", type=float, required=True, help="sphere radius")
    ap.add_argument("--a", type=float, default=1.0, help="rod radius")
    ap.add_argument("--frame", type=int, default=-1)
    ap.add_argument("--z0", type=float, default=0.0, help="height of the cut")
    ap.add_argument("--out")
    a = ap.parse_args()

    with Trajectory(a.file) as t:
        chains, step = t.frame(a.frame), int(t.steps[a.frame])
        energy = None
        if "bend.energy" in t.fields:
            energy = [e.reshape(-1) for e in t.frame(a.frame, "bend.energy")]
    runs, run_energy = inside_runs(chains, energy, a.R + 2 * a.a)
    fig = plt.figure(figsize=(11, 5))
    ax = fig.add_subplot(1, 2, 1, projection="3d")
    lc = plot.packing3d(ax, runs, values=run_energy, radius=a.R, linewidth=2.5)
    if energy is not None:
        fig.colorbar(lc, ax=ax, shrink=0.6, label="bending energy per node")
    ax.set_title(f"step {step}: {sum(len(r) - 1 for r in runs)} segments inside")
    # the cut: nodes in a slab around z0, drawn as discs of the rod's radius
    ax2 = fig.add_subplot(1, 2, 2)
    n = plot.section(ax2, runs, a.a, a.z0, values=run_energy, sphere_radius=a.R)
    ax2.set_title(f"cut |z - {a.z0:g}| < a: {n} nodes")
    fig.tight_layout()
    out = a.out or a.file.rsplit(".", 1)[0] + f"_frame{a.frame}.png"
    fig.savefig(out, dpi=110)
    print("wrote", out)


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Render a 3D packing frame (slender h5md dump of examples/pack3d) as a PNG: the rod
as a thick line in 3D coloured by the per-node bending energy (bend.energy, if
dumped), and a cut through the middle of the sphere: the rod's cross-sections
within a slab |z - z0| < a drawn as discs of radius a.

  /usr/bin/python3 scripts/render_pack3d.py low_torsion.h5 --R 10 [--frame -1] [--out packing.png]
"""
import argparse

import h5py
import numpy as np


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("file")
    ap.add_argument("--R", type=float, required=True, help="sphere radius")
    ap.add_argument("--a", type=float, default=1.0, help="rod radius")
    ap.add_argument("--frame", type=int, default=-1)
    ap.add_argument("--z0", type=float, default=0.0, help="height of the cut")
    ap.add_argument("--out")
    a = ap.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PatchCollection
    from mpl_toolkits.mplot3d.art3d import Line3DCollection

    with h5py.File(a.file, "r") as h:
        pos = h["particles/all/position/value"][a.frame]
        step = h["particles/all/position/step"][a.frame]
        energy = None
        if "particles/all/bend.energy" in h:
            energy = np.asarray(h["particles/all/bend.energy/value"][a.frame]).reshape(-1)
    inside = np.linalg.norm(pos, axis=1) < a.R + 2 * a.a
    segs = np.stack([pos[:-1], pos[1:]], axis=1)
    keep = inside[:-1] & inside[1:]
    fig = plt.figure(figsize=(11, 5))
    ax = fig.add_subplot(1, 2, 1, projection="3d")
    colour = 0.5 * (energy[:-1] + energy[1:]) if energy is not None else np.zeros(len(segs))
    lc = Line3DCollection(segs[keep], linewidths=2.5, cmap="viridis")
    lc.set_array(colour[keep])
    ax.add_collection(lc)
    for s in (-1, 1):
        ax.set_xlim(-a.R, a.R)
        ax.set_ylim(-a.R, a.R)
        ax.set_zlim(-a.R, a.R)
    ax.set_box_aspect((1, 1, 1))
    if energy is not None:
        fig.colorbar(lc, ax=ax, shrink=0.6, label="bending energy per node")
    ax.set_title(f"step {step}: {int(keep.sum())} segments inside")
    # the cut: nodes in a slab around z0, drawn as discs of the rod's radius
    ax2 = fig.add_subplot(1, 2, 2)
    slab = inside & (np.abs(pos[:, 2] - a.z0) < a.a)
    circles = [plt.Circle((x, y), a.a) for x, y in pos[slab, :2]]
    pc = PatchCollection(circles, cmap="viridis", edgecolor="k", linewidth=0.3)
    pc.set_array(energy[slab] if energy is not None else np.zeros(slab.sum()))
    ax2.add_collection(pc)
    rz = np.sqrt(max(a.R ** 2 - a.z0 ** 2, 0.0))
    ax2.add_patch(plt.Circle((0, 0), rz, fill=False, color="k"))
    ax2.set_xlim(-a.R, a.R)
    ax2.set_ylim(-a.R, a.R)
    ax2.set_aspect("equal")
    ax2.set_title(f"cut |z - {a.z0:g}| < a: {int(slab.sum())} nodes")
    fig.tight_layout()
    out = a.out or a.file.rsplit(".", 1)[0] + f"_frame{a.frame}.png"
    fig.savefig(out, dpi=110)
    print("wrote", out)


if __name__ == "__main__":
    main()

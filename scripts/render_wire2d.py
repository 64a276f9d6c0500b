#!/usr/bin/python3
"""Render a frame of a 2D wire trajectory (slender `h5md` dump) as a PNG.

The wire is drawn as a thick line whose width is the wire diameter in data
units (so it looks like a real wire), each segment coloured by the elastic
bending energy of its two end nodes, inside the cavity circle -- like the
snapshots of crumpled-wire papers.

Input layout (H5MD, see styles/dump/h5md.cpp):
    /particles/all/position/{value,step,time}   value: [frames, Nmax, 2]
    /connectivity/edges/value                   [frames, Emax, 2] int64
    /particles/all/bend.plastic_curvature/value [frames, Nmax, 1] (optional)
Arrays are padded with zeros past the valid rows of a frame; an edge row (0, 0)
is padding.  Only nodes referenced by valid edges are drawn.

Bending energy per interior node (chain order a -> m -> b, as bend2d does):
    zeta = atan2(e0 x e1, e0 . e1),  e0 = x_m - x_a,  e1 = x_b - x_m
    E = 1/2 k2 zeta^2                       (default)
    E = 1/2 k2 (zeta - kappa_pl l0)^2       (--plastic: recoverable energy)
Chain end nodes have no hinge and get E = 0.

Usage:
    render_wire2d.py classic.h5                       # last frame -> classic_frame<k>.png
    render_wire2d.py classic.h5 --frame 3 --radius 40 --log --out snap.png
    render_wire2d.py classic.h5 --all --out-dir frames/ --radius 40
"""

import argparse
import math
import os
import sys

import h5py
import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402
from matplotlib.colors import LogNorm, Normalize  # noqa: E402
from matplotlib.patches import Circle  # noqa: E402

POS = "/particles/all/position"
EDGES = "/connectivity/edges/value"
PLASTIC = "/particles/all/bend.plastic_curvature/value"


def n_frames(f):
    """Frames present in both the position and the edge series."""
    return min(f[POS + "/value"].shape[0], f[EDGES].shape[0])


def read_frame(f, t, want_plastic):
    """Return (pos [Nmax,2], edges [E,2] valid only, step, time, kappa_pl or None)."""
    pos = np.asarray(f[POS + "/value"][t], dtype=float)[:, :2]
    edges = np.asarray(f[EDGES][t], dtype=np.int64)
    edges = edges[~((edges[:, 0] == 0) & (edges[:, 1] == 0))]  # drop (0,0) padding
    step = int(f[POS + "/step"][t])
    time = float(f[POS + "/time"][t])
    kpl = None
    if want_plastic:
        if PLASTIC in f:
            kpl = np.asarray(f[PLASTIC][t], dtype=float).reshape(pos.shape[0], -1)[:, 0]
        else:
            print("warning: no bend.plastic_curvature in file; using elastic energy 1/2 k2 zeta^2",
                  file=sys.stderr)
    return pos, edges, step, time, kpl


def polylines(edges):
    """Split the chain-ordered edge list into node sequences.

    A new polyline starts whenever an edge's first node differs from the
    previous edge's second node.  A closed chain comes back as a sequence whose
    first and last nodes coincide.
    """
    if len(edges) == 0:
        return []
    breaks = np.flatnonzero(edges[1:, 0] != edges[:-1, 1]) + 1
    lines = []
    for chunk in np.split(edges, breaks):
        lines.append(np.concatenate([chunk[:, 0], chunk[-1:, 1]]))
    return lines


def node_energy(pos, lines, k2, kpl=None, l0=1.0):
    """Bending energy per node (zeros for chain ends and unused nodes)."""
    energy = np.zeros(pos.shape[0])
    for nodes in lines:
        closed = len(nodes) > 3 and nodes[0] == nodes[-1]
        if closed:  # hinge at the closing node too: wrap a -> m -> b around
            nodes = np.concatenate([nodes[-2:-1], nodes])
        if len(nodes) < 3:
            continue
        a, m, b = nodes[:-2], nodes[1:-1], nodes[2:]
        e0 = pos[m] - pos[a]
        e1 = pos[b] - pos[m]
        cross = e0[:, 0] * e1[:, 1] - e0[:, 1] * e1[:, 0]
        dot = np.sum(e0 * e1, axis=1)
        zeta = np.arctan2(cross, dot)
        if kpl is not None:
            zeta = zeta - kpl[m] * l0
        energy[m] = 0.5 * k2 * zeta**2
    return energy


def render(pos, edges, energy, step, time, args, out_path):
    """Draw one frame and save it to out_path."""
    a, b = edges[:, 0], edges[:, 1]
    segs = np.stack([pos[a], pos[b]], axis=1)  # [E, 2 (ends), 2 (xy)]
    seg_e = 0.5 * (energy[a] + energy[b])  # segment colour: mean of its end nodes

    center = np.asarray(args.center, dtype=float)
    used = np.unique(edges)
    rmax = float(np.max(np.linalg.norm(pos[used] - center, axis=1))) if len(used) else 1.0
    radius = args.radius if args.radius is not None else max(math.ceil(rmax), 1)

    # Colour scale (fixed with --vmin/--vmax, e.g. for a consistent movie).
    vmax = args.vmax if args.vmax is not None else (float(seg_e.max()) if len(seg_e) else 1.0)
    vmax = vmax if vmax > 0 else 1.0
    if args.log:
        positive = seg_e[seg_e > 0]
        vmin = args.vmin if args.vmin else (max(positive.min(), vmax * 1e-6) if len(positive) else vmax * 1e-6)
        norm = LogNorm(vmin=vmin, vmax=vmax, clip=True)
        seg_e = np.maximum(seg_e, vmin)  # zero-energy ends would be masked on a log scale
    else:
        norm = Normalize(vmin=args.vmin if args.vmin is not None else 0.0, vmax=vmax)

    fig, ax = plt.subplots(figsize=(args.size, args.size * 0.85), dpi=args.dpi)
    lc = LineCollection(segs, cmap="viridis", norm=norm, capstyle="round", joinstyle="round")
    lc.set_array(seg_e)
    ax.add_collection(lc)
    ax.add_patch(Circle(center, radius, fill=False, edgecolor="black", linewidth=1.2))
    cb = fig.colorbar(lc, ax=ax, fraction=0.046, pad=0.04)
    cb.set_label("bending energy")

    # Limits: the cavity plus a margin (and the wire, should it stick out).
    half = max(radius, rmax + 0.5 * args.diameter) * 1.04
    ax.set_xlim(center[0] - half, center[0] + half)
    ax.set_ylim(center[1] - half, center[1] + half)
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel("x")
    ax.set_ylabel("y")

    # Line width in points = diameter in data units: measure the final data ->
    # pixel scale (after the colorbar took its space and the aspect is applied).
    ax.apply_aspect()
    px_per_unit = ax.transData.transform((1.0, 0.0))[0] - ax.transData.transform((0.0, 0.0))[0]
    pt_per_unit = px_per_unit * 72.0 / fig.dpi
    lc.set_linewidth(args.diameter * pt_per_unit)

    title = f"step {step}, t = {time:.6g}"
    if args.radius is not None:
        mid = 0.5 * (pos[a] + pos[b])
        inside = int(np.count_nonzero(np.linalg.norm(mid - center, axis=1) < radius))
        phi = args.diameter * inside * args.l0 / (math.pi * radius**2)
        title += f", $\\phi$ = {phi:.4f}"
    ax.set_title(title)

    fig.savefig(out_path, dpi=fig.dpi)  # same dpi as the scale computed above
    plt.close(fig)


def render_index(f, t, args, out_path):
    pos, edges, step, time, kpl = read_frame(f, t, args.plastic)
    if len(edges) == 0:
        print(f"frame {t}: no edges, skipped", file=sys.stderr)
        return
    energy = node_energy(pos, polylines(edges), args.k2, kpl, args.l0)
    render(pos, edges, energy, step, time, args, out_path)
    print(f"frame {t} (step {step}): {len(np.unique(edges))} nodes, {len(edges)} edges, "
          f"max node energy {energy.max():.4g} -> {out_path}")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("file", help="H5MD trajectory written by slender's h5md dump")
    p.add_argument("--frame", type=int, default=-1, help="frame index (default -1 = last)")
    p.add_argument("--out", help="PNG path (default <file>_frame<k>.png)")
    p.add_argument("--all", action="store_true", help="render every frame into --out-dir")
    p.add_argument("--out-dir", default=None, help="folder for --all (default: next to the file)")
    p.add_argument("--dpi", type=float, default=150)
    p.add_argument("--size", type=float, default=7.0, help="figure width in inches (default 7)")
    p.add_argument("--diameter", type=float, default=1.0, help="wire diameter in data units")
    p.add_argument("--radius", type=float, default=None,
                   help="cavity radius (default: max node distance from the centre, rounded up); "
                        "giving it also prints the packing density in the title")
    p.add_argument("--center", type=float, nargs=2, default=[0.0, 0.0], metavar=("X", "Y"))
    p.add_argument("--k2", type=float, default=60.0, help="bending stiffness k2 (default 60)")
    p.add_argument("--l0", type=float, default=1.0, help="rest edge length (default 1)")
    p.add_argument("--plastic", action="store_true",
                   help="recoverable energy 1/2 k2 (zeta - kappa_pl l0)^2 from bend.plastic_curvature")
    p.add_argument("--log", action="store_true", help="logarithmic colour scale")
    p.add_argument("--vmin", type=float, default=None, help="colour scale minimum")
    p.add_argument("--vmax", type=float, default=None, help="colour scale maximum")
    args = p.parse_args(argv)

    stem = os.path.splitext(args.file)[0]
    with h5py.File(args.file, "r") as f:
        T = n_frames(f)
        if T == 0:
            sys.exit(f"{args.file}: no frames")
        if args.all:
            out_dir = args.out_dir or os.path.dirname(os.path.abspath(args.file))
            os.makedirs(out_dir, exist_ok=True)
            base = os.path.basename(stem)
            for t in range(T):
                render_index(f, t, args, os.path.join(out_dir, f"{base}_frame{t:04d}.png"))
        else:
            if not -T <= args.frame < T:
                sys.exit(f"{args.file}: frame {args.frame} out of range ({T} frames)")
            t = args.frame % T
            render_index(f, t, args, args.out or f"{stem}_frame{t}.png")


if __name__ == "__main__":
    main()

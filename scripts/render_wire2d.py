#!/usr/bin/python3
"""Render a frame of a 2D wire trajectory (slender `h5md` dump) as a PNG.

The wire is drawn as a thick line whose width is the wire diameter in data
units (so it looks like a real wire), each segment coloured by the elastic
bending energy of its two end nodes, inside the cavity circle -- like the
snapshots of crumpled-wire papers.

The trajectory is read by slender.io (python/slender) as ordered chains; the
plastic curvature comes from the dumped field bend.plastic_curvature (optional).
Only nodes on a chain's edges are drawn.

Bending energy per node (chain order a -> m -> b, as bend2d does):
    zeta = atan2(e0 x e1, e0 . e1),  e0 = x_m - x_a,  e1 = x_b - x_m
    E = 1/2 k2 zeta^2                       (default)
    E = 1/2 k2 (zeta - kappa_pl l0)^2       (--plastic: recoverable energy)
The end nodes of an open chain have no hinge and get E = 0.

Usage:
    render_wire2d.py classic.h5                       # last frame -> classic_frame<k>.png
    render_wire2d.py classic.h5 --frame 3 --radius 40 --log --out snap.png
    render_wire2d.py classic.h5 --all --out-dir frames/ --radius 40
"""

import argparse
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))
from slender import plot  # noqa: E402  (selects the Agg backend)
from slender.io import Trajectory  # noqa: E402

import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import LogNorm, Normalize  # noqa: E402

PLASTIC = "bend.plastic_curvature"


def node_energy(points, closed, k2, kpl=None, l0=1.0):
    """Bending energy per node of one chain in chain order (zero at an open chain's ends)."""
    n = len(points)
    energy = np.zeros(n)
    idx = np.arange(n)
    if closed:  # a hinge at every node, wrapping around
        a, m, b = np.roll(idx, 1), idx, np.roll(idx, -1)
    elif n >= 3:
        a, m, b = idx[:-2], idx[1:-1], idx[2:]
    else:
        return energy
    e0 = points[m] - points[a]
    e1 = points[b] - points[m]
    cross = e0[:, 0] * e1[:, 1] - e0[:, 1] * e1[:, 0]
    zeta = np.arctan2(cross, np.sum(e0 * e1, axis=1))
    if kpl is not None:
        zeta = zeta - kpl[m] * l0
    energy[m] = 0.5 * k2 * zeta**2
    return energy


def render(chains, closed, energy, step, time, args, out_path):
    """Draw one frame (ordered chains with per-node energies) and save it to out_path."""
    center = np.asarray(args.center, dtype=float)
    rmax = max(float(np.max(np.linalg.norm(c - center, axis=1))) for c in chains)
    radius = args.radius if args.radius is not None else max(math.ceil(rmax), 1)

    fig, ax = plt.subplots(figsize=(args.size, args.size * 0.85), dpi=args.dpi)
    lc = plot.wire2d(ax, chains, closed, energy, radius=radius, center=center,
                     margin=0.5 * args.diameter)
    seg_e = lc.get_array()  # segment colour: mean of its end nodes

    # Colour scale (fixed with --vmin/--vmax, e.g. for a consistent movie).
    vmax = args.vmax if args.vmax is not None else (float(seg_e.max()) if len(seg_e) else 1.0)
    vmax = vmax if vmax > 0 else 1.0
    if args.log:
        positive = seg_e[seg_e > 0]
        vmin = args.vmin if args.vmin else (max(positive.min(), vmax * 1e-6) if len(positive) else vmax * 1e-6)
        lc.set_norm(LogNorm(vmin=vmin, vmax=vmax, clip=True))
        lc.set_array(np.maximum(seg_e, vmin))  # zero-energy ends would be masked on a log scale
    else:
        lc.set_norm(Normalize(vmin=args.vmin if args.vmin is not None else 0.0, vmax=vmax))
    cb = fig.colorbar(lc, ax=ax, fraction=0.046, pad=0.04)
    cb.set_label("bending energy")
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    # the final layout is set (colour bar placed): the wire at its diameter
    plot.set_width_in_data_units(ax, lc, args.diameter)

    title = f"step {step}, t = {time:.6g}"
    if args.radius is not None:
        segs, _ = plot.segments(chains, closed)
        mid = segs.mean(axis=1)
        inside = int(np.count_nonzero(np.linalg.norm(mid - center, axis=1) < radius))
        phi = args.diameter * inside * args.l0 / (math.pi * radius**2)
        title += f", $\\phi$ = {phi:.4f}"
    ax.set_title(title)

    fig.savefig(out_path, dpi=fig.dpi)  # same dpi as the scale computed above
    plt.close(fig)


def render_index(t, i, args, out_path):
    chains, closed = t.frame(i), t.closed(i)
    if not chains:
        print(f"frame {i}: no edges, skipped", file=sys.stderr)
        return
    chains = [c[:, :2] for c in chains]
    kpl = [None] * len(chains)
    if args.plastic:
        if PLASTIC in t.fields:
            kpl = [k.reshape(len(k), -1)[:, 0] for k in t.frame(i, PLASTIC)]
        else:
            print("warning: no bend.plastic_curvature in file; using elastic energy 1/2 k2 zeta^2",
                  file=sys.stderr)
    energy = [node_energy(c, ring, args.k2, k, args.l0) for c, ring, k in zip(chains, closed, kpl)]
    step, time = int(t.steps[i]), float(t.times[i])
    render(chains, closed, energy, step, time, args, out_path)
    nodes = sum(len(c) for c in chains)
    edges = sum(len(c) if ring else len(c) - 1 for c, ring in zip(chains, closed))
    print(f"frame {i} (step {step}): {nodes} nodes, {edges} edges, "
          f"max node energy {max(e.max() for e in energy):.4g} -> {out_path}")


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
    with Trajectory(args.file) as f:
        T = len(f)
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

#!/usr/bin/env python3
"""A gallery of crumpled 2D wires: one panel per run, the wire drawn at its true diameter inside
its cavity, titled with the run's packing fraction, A/B, loops and wall contacts.

  /usr/bin/python3 scripts/wire_gallery.py OUT.png "classic, seed 4=results/X/points/v0.001_seed4.npy" ...

Each POINTS.npy is a wire's final node positions in chain order as scripts/crumple_study.py keeps
them (results/<study>/points/), with its run record POINTS.json beside it (the deck's RESULT:
f, phi, ab_ratio, loops, wall_contacts). The cavity is drawn with radius f (the deck's units:
wire diameter 1).
"""
import argparse
import json
import os
import sys

import numpy as np


def load(spec):
    """(title, xy, result) from "TITLE=PATH.npy"."""
    if "=" not in spec:
        sys.exit(f"wire_gallery: '{spec}' is not TITLE=POINTS.npy")
    title, path = spec.rsplit("=", 1)  # the title may hold "=" itself
    record = os.path.splitext(path)[0] + ".json"
    if not os.path.exists(path) or not os.path.exists(record):
        sys.exit(f"wire_gallery: {path} needs its positions and its run record {record}")
    xy = np.load(path)
    if xy.ndim != 2 or xy.shape[1] < 2 or len(xy) < 2:
        sys.exit(f"wire_gallery: {path} holds no wire (shape {xy.shape})")
    with open(record) as fh:
        result = json.load(fh).get("result") or {}
    if "f" not in result:
        sys.exit(f"wire_gallery: {record} has no RESULT with the cavity size f")
    return title, xy[:, :2], result


def caption(result):
    parts = []
    for key, fmt in (("phi", "φ {:.3f}"), ("ab_ratio", "A/B {:.2f}"), ("loops", "{:.0f} loops"),
                     ("wall_contacts", "{:.0f} wall contacts")):
        if key in result:
            parts.append(fmt.format(float(result[key])))
    return ", ".join(parts)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", help="the PNG to write")
    ap.add_argument("runs", nargs="+", help="TITLE=POINTS.npy, one per panel")
    ap.add_argument("--columns", type=int, default=0, help="panels per row (default: all in one row up to 3)")
    ap.add_argument("--size", type=float, default=5.0, help="panel size in inches")
    args = ap.parse_args(argv)
    runs = [load(s) for s in args.runs]
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    ncol = args.columns or min(3, len(runs))
    nrow = (len(runs) + ncol - 1) // ncol
    fig, axes = plt.subplots(nrow, ncol, figsize=(args.size * ncol, args.size * nrow + 0.4), squeeze=False)
    t = np.linspace(0, 2 * np.pi, 400)
    for ax in axes.flat[len(runs):]:
        ax.axis("off")
    for (title, xy, result), ax in zip(runs, axes.flat):
        r = float(result["f"])
        span = 1.08 * r
        ax.set_xlim(-span, span)
        ax.set_ylim(-span, span)
        ax.set_aspect("equal")
        ax.axis("off")
        # the wire at its diameter (1 in the deck's units): points per data unit of this panel
        width_pt = ax.get_position().width * fig.get_figwidth() * 72 / (2 * span)
        ax.plot(r * np.cos(t), r * np.sin(t), color="0.55", lw=max(0.6, width_pt))
        ax.plot(xy[:, 0], xy[:, 1], color="k", lw=max(0.2, width_pt), solid_capstyle="round")
        ax.set_title(f"{title}\n{caption(result)}", fontsize=10)
    fig.tight_layout()
    fig.savefig(args.out, dpi=110, bbox_inches="tight")
    print(f"wrote {args.out} ({len(runs)} wires)")


if __name__ == "__main__":
    main()

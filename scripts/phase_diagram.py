#!/usr/bin/env python3
"""Morphological phase diagram of the 2D crumpled wire (W2-4, docs/models.md §7.2):
yield curvature kappa_theta x static friction mu_st, several seeds per point, each
run to jamming and classified (docs/models.md §2.7):

  spiral   winding of a half of the wire >= 2 turns and at most 2 loops
  classic  A/B < 0.5 (squared curvature concentrated near the wall)
  plastic  otherwise

A command-line entry point over workflows/phase_diagram.smk: the grid is a Snakemake run
(one job per run, resumable from checkpoints, a deleted or missing point runs alone;
workflows/README.md), locally on --cores or on Slurm with --profile slurm. Its results
stay under --results; the table and pictures are copied to <out>.csv, <out>.png (majority
class per point, with its share), <out>_phi.png (mean jamming density) and
<out>_thumbnails.png (the final wire of each point). The functions below classify and
draw; the workflow imports them.

  /usr/bin/python3 scripts/phase_diagram.py                      # the thesis' sweep, f = 50
  /usr/bin/python3 scripts/phase_diagram.py --f 10 --yields 0 0.02 0.04 0.06 \\
      --mus 0 0.2 0.4 0.6 --seeds 1 --out docs/crumple2d/phase_diagram_f10
  /usr/bin/python3 scripts/phase_diagram.py --dry-run            # what would run, and why
"""
import argparse
import csv
import os
import sys

import numpy as np

import workflow_cli

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FIELDS = ["f", "s", "yield", "mu", "seed", "class", "phi", "jammed", "loops", "winding", "ab_ratio",
          "contacts", "steps", "wall_s", "dt", "status", "error"]


def classify(row, min_winding=2.0, max_loops=2):
    if float(row["winding"]) >= min_winding and float(row["loops"]) <= max_loops:
        return "spiral"
    return "classic" if float(row["ab_ratio"]) < 0.5 else "plastic"


def load(path):
    if not os.path.exists(path):
        return []
    with open(path) as fh:
        return list(csv.DictReader(fh))


def draw(rows, out, yields, mus, f):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    classes = ["spiral", "plastic", "classic"]
    colours = {"spiral": "#4c72b0", "plastic": "#dd8452", "classic": "#55a868"}
    ok = [r for r in rows if r["status"] in ("ok", "unstable")]
    fig, ax = plt.subplots(figsize=(8, 5))
    grid_phi = np.full((len(mus), len(yields)), np.nan)
    for i, mu in enumerate(mus):
        for j, y in enumerate(yields):
            pts = [r for r in ok if abs(float(r["yield"]) - y) < 1e-9 and abs(float(r["mu"]) - mu) < 1e-9]
            if not pts:
                continue
            counts = {c: sum(r["class"] == c for r in pts) for c in classes}
            top = max(classes, key=lambda c: counts[c])
            share = counts[top] / len(pts)
            shaky = any(r["status"] == "unstable" for r in pts)  # classified from the last good state
            ax.scatter(y, mu, s=300 * share + 40, c=colours[top], marker="s",
                       edgecolors="r" if shaky else "k", linewidths=1.5 if shaky else 0.3)
            ax.annotate(f"{counts[top]}/{len(pts)}", (y, mu), fontsize=6, ha="center", va="center")
            grid_phi[i, j] = np.mean([float(r["phi"]) for r in pts])
    for c in classes:
        ax.scatter([], [], c=colours[c], marker="s", label=c)
    ax.set_xlabel("yield curvature kappa_theta")
    ax.set_ylabel("static friction mu_st")
    ax.set_title(f"2D crumpling phase diagram, f = {f:g} (majority class, count/seeds)", fontsize=9)
    ax.scatter([], [], c="w", marker="s", edgecolors="r", linewidths=1.5, label="guard stop (last good state)")
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.tight_layout()
    fig.savefig(out + ".png", dpi=120)
    plt.close(fig)
    fig, ax = plt.subplots(figsize=(6, 5))
    im = ax.imshow(grid_phi, origin="lower", aspect="auto",
                   extent=[yields[0], yields[-1], mus[0], mus[-1]] if len(yields) > 1 and len(mus) > 1 else None)
    fig.colorbar(im, label="mean jamming density phi")
    ax.set_xlabel("yield curvature kappa_theta")
    ax.set_ylabel("static friction mu_st")
    fig.tight_layout()
    fig.savefig(out + "_phi.png", dpi=120)
    plt.close(fig)


def config_args(a):
    """The workflow's --config of these arguments."""
    lists = workflow_cli.yaml_list
    cfg = [f"slender={os.path.abspath(a.slender)}", f"results={a.results}", f"deck={a.deck}",
           f"f={a.f:g}", f"s={a.s:g}", f"yields={lists(a.yields)}", f"mus={lists(a.mus)}",
           f"seeds={lists(a.seeds)}", f"checkpoint_every={a.checkpoint_every}"]
    if a.timeout:
        cfg.append(f"timeout={a.timeout:g}")
    if not a.retry_dt:
        cfg.append("retry_unstable=")  # empty: None (Snakemake reads "null" as a string)
    variables = a.var + ([f"max_steps={a.max_steps:.0f}"] if a.max_steps else [])
    if variables:
        cfg.append("vars=" + workflow_cli.yaml_vars(variables))
    return cfg


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--slender", default=os.path.join(ROOT, "build", "slender"))
    ap.add_argument("--deck", default="classic", help="examples/crumple2d/<deck>.lua")
    ap.add_argument("--f", type=float, default=50)
    ap.add_argument("--s", type=float, default=0.05, help="feed speed (the thesis' s, reading (a))")
    ap.add_argument("--yields", type=float, nargs="+", default=[round(0.005 * i, 3) for i in range(13)])
    ap.add_argument("--mus", type=float, nargs="+", default=[round(0.05 * i, 2) for i in range(13)])
    ap.add_argument("--seeds", type=int, nargs="+", default=list(range(1, 10)))
    ap.add_argument("--max-steps", type=float, default=None, help="-v max_steps of every run")
    ap.add_argument("--var", action="append", default=[], metavar="NAME=VALUE",
                    help="a further -v variable of every run (repeatable), e.g. max_phi=0.3")
    ap.add_argument("--timeout", type=float, default=None, help="seconds per run (a cut run continues next time)")
    ap.add_argument("--checkpoint-every", type=int, default=1000000, help="steps between a run's checkpoints")
    ap.add_argument("--no-retry-dt", dest="retry_dt", action="store_false",
                    help="do not repeat a run stopped by the instability guard with half the step")
    ap.add_argument("--results", default=None,
                    help="the workflow's results folder (default results/phase_diagram_f<f> in the "
                         "repository); runs already there are not run again")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "crumple2d", "phase_diagram_f50"))
    workflow_cli.add_options(ap, max(1, os.cpu_count() or 2))
    a = ap.parse_args()
    a.results = os.path.abspath(a.results or os.path.join(ROOT, "results", f"phase_diagram_f{a.f:g}"))
    done = workflow_cli.run("phase_diagram", config_args(a), a)
    if a.dry_run or done != 0:
        return done
    workflow_cli.copy_outputs(os.path.join(a.results, f"phase_diagram_f{a.f:g}"), a.out,
                              (".csv", ".png", "_phi.png", "_thumbnails.png"))
    rows = load(a.out + ".csv")
    ok = sum(r["status"] == "ok" for r in rows)
    unstable = sum(r["status"] == "unstable" for r in rows)
    print(f"{ok} ok, {unstable} unstable (classified from the last good state), "
          f"{len(rows) - ok - unstable} failed; wrote {a.out}.csv, .png, _phi.png, _thumbnails.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())

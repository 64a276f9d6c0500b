#!/usr/bin/env python3
"""Maximum packing fraction against a/R for the 3D packing decks (docs/models.md §5.4):
runs examples/pack3d/<setup>.lua for each sphere radius R and seed until the stop
force, and writes <out>.csv (one row per run), <out>.png (phi_max against a/R with a
power-law fit phi_max = A (a/R)^p per setup, fitted on the seed means) and <out>_fit.csv.

A command-line entry point over workflows/pack3d.smk: the sweep is a Snakemake run (one
job per run, resumable from checkpoints, only missing runs run; workflows/README.md),
locally on --cores or on Slurm with --profile slurm; its results stay under --results and
the table and picture are copied to --out.

  /usr/bin/python3 scripts/pack3d_sweep.py --setups low_torsion --R 4 5 10 13 20 --seeds 1 2 3

A run too long for one sitting (scripts/long_run.sh, $SLENDER_RUNS/<name>/) joins the
table once it has finished: --add-long-run ../slender-runs/lt20 takes its result.json and,
for the cost, the wall time and node-steps summed over all its segments (segments.csv).
The R = 20 runs recorded in docs/results/long_runs/ are added the same way:
--add-long-run docs/results/long_runs/lt20 docs/results/long_runs/ht20.
"""
import argparse
import csv
import math
import os
import sys

import numpy as np

import workflow_cli

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FIELDS = ["setup", "R", "a_over_R", "seed", "phi", "stopped", "force_R2_over_YI", "bend_R_over_YI",
          "rg_over_R", "stretch_over_bend", "contacts", "nodes", "steps", "wall_s", "node_steps_per_s",
          "status", "error"]


def long_run_row(store):
    """One table row from a finished long run: the deck's summary, with the wall time and
    node-steps/s of the whole run (every sitting, steps redone after a restart included)
    instead of those of its last sitting."""
    import json
    path = os.path.join(store, "result.json")
    # long_run.sh writes result.json (with `finished`) only when the deck ended by itself
    if not os.path.exists(path):
        raise SystemExit(f"pack3d_sweep: {store} has not finished (no result.json)")
    with open(path) as fh:
        res = json.load(fh)
    with open(os.path.join(store, "segments.csv")) as fh:
        seg = list(csv.DictReader(fh))
    wall = sum(float(r["wall_s"]) for r in seg)
    node_steps = sum(float(r["node_steps"]) for r in seg)
    setup = res["case"].split("/")[-1]
    row = {k: res[k] for k in FIELDS if k in res}
    row.update(setup=setup, a_over_R=1.0 / float(res["R"]), wall_s=wall,
               node_steps_per_s=node_steps / wall, status="ok")
    return row


def load(path):
    if not os.path.exists(path):
        return []
    with open(path) as fh:
        return list(csv.DictReader(fh))


def fit_power(x, y):
    b, c = np.polyfit(np.log(x), np.log(y), 1)
    return math.exp(c), b


def draw(rows, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5.5, 4))
    summary = []
    for setup in sorted({r["setup"] for r in rows}):
        ok = [r for r in rows if r["setup"] == setup and r["status"] == "ok"]
        if not ok:
            continue
        Rs = sorted({float(r["R"]) for r in ok})
        mean = [np.mean([float(r["phi"]) for r in ok if float(r["R"]) == R]) for R in Rs]
        std = [np.std([float(r["phi"]) for r in ok if float(r["R"]) == R]) for R in Rs]
        x = 1.0 / np.array(Rs)
        bars = ax.errorbar(x, mean, yerr=std, fmt="o", label=setup)
        if len(Rs) >= 3:
            A, p = fit_power(x, np.array(mean))
            xs = np.geomspace(x.min(), x.max(), 50)
            ax.plot(xs, A * xs ** p, "-", color=bars[0].get_color(), label=f"{setup}: {A:.3g} (a/R)^{p:.2f}")
            summary.append((setup, A, p))
    ax.set_xscale("log")
    ax.set_yscale("log")
    # plain numbers at the radii run and at round densities (a log axis spanning less
    # than a decade has no major ticks of its own)
    from matplotlib.ticker import FixedLocator, NullFormatter, NullLocator
    Rs_all = sorted({float(r["R"]) for r in rows if r["status"] == "ok"})
    ax.xaxis.set_major_locator(FixedLocator([1.0 / R for R in Rs_all]))
    ax.xaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: f"1/{1 / v:.0f}"))
    ax.xaxis.set_minor_locator(NullLocator())
    ax.yaxis.set_major_locator(FixedLocator([k / 10 for k in range(1, 11)]))
    ax.yaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:.1f}"))
    ax.yaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel("a / R")
    ax.set_ylabel("phi_max")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out + ".png", dpi=120)
    plt.close(fig)
    return summary


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--slender", default=os.path.join(ROOT, "build", "slender"))
    ap.add_argument("--setups", nargs="+", default=["low_torsion"])
    ap.add_argument("--R", type=float, nargs="+", default=[4, 5, 10, 13, 20])
    ap.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    ap.add_argument("--timeout", type=float, default=None, help="seconds per run (a cut run continues next time)")
    ap.add_argument("--checkpoint-every", type=int, default=1000000, help="steps between a run's checkpoints")
    ap.add_argument("--results", default=None,
                    help="the workflow's results folder (default results/pack3d in the repository); "
                         "runs already there are not run again")
    workflow_cli.add_options(ap, max(1, os.cpu_count() or 2))
    ap.add_argument("--var", action="append", default=[], metavar="NAME=VALUE",
                    help="extra -v override for every run (repeatable)")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "pack3d", "phi_max"))
    ap.add_argument("--add-long-run", nargs="+", default=[], metavar="RUNS/NAME",
                    help="add finished long runs (scripts/long_run.sh) to the table and redraw")
    a = ap.parse_args()
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    path = a.out + ".csv"
    rows = load(path)
    if a.add_long_run:
        new = [long_run_row(store) for store in a.add_long_run]
        keep = [r for r in rows if not any(r["setup"] == n["setup"] and float(r["R"]) == float(n["R"])
                                           and int(r["seed"]) == int(n["seed"]) for n in new)]
        with open(path, "w", newline="") as fh:
            w = csv.DictWriter(fh, FIELDS)
            w.writeheader()
            w.writerows(keep + new)
        for n in new:
            print(f"{n['setup']} R {n['R']} seed {n['seed']}: phi {n['phi']}, {n['steps']} steps, "
                  f"{n['wall_s']:.0f} s, {n['node_steps_per_s']:.3g} node-steps/s")
        for setup, A, p in draw(load(path), a.out):
            print(f"{setup}: phi_max = {A:.4g} (a/R)^{p:.3f}")
        return 0
    results = os.path.abspath(a.results or os.path.join(ROOT, "results", "pack3d"))
    lists = workflow_cli.yaml_list
    cfg = [f"slender={os.path.abspath(a.slender)}", f"results={results}", f"setups={lists(a.setups)}",
           f"R={lists(a.R)}", f"seeds={lists(a.seeds)}", f"checkpoint_every={a.checkpoint_every}"]
    if a.timeout:
        cfg.append(f"timeout={a.timeout:g}")
    if a.var:
        cfg.append("vars=" + workflow_cli.yaml_vars(a.var))
    done = workflow_cli.run("pack3d", cfg, a)
    if a.dry_run or done != 0:
        return done
    workflow_cli.copy_outputs(os.path.join(results, "phi_max"), a.out, (".csv", ".png", "_fit.csv"))
    for setup, A, p in draw(load(a.out + ".csv"), a.out):
        print(f"{setup}: phi_max = {A:.4g} (a/R)^{p:.3f}")
    print("wrote", a.out + ".csv", a.out + ".png")
    return 0


if __name__ == "__main__":
    sys.exit(main())

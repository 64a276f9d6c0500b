#!/usr/bin/env python3
"""Where the straight wire first buckles, against the feed speed (docs/models.md §7.2: "the
straight wire first buckles up or down and stays stable until it first touches the wall").

Runs a crumpling deck from its straight start until `--feed` d of wire (per channel, as a
fraction of the cavity radius) has entered, for each cavity size f and feed speed v, and
measures the buckled wire:
  - peak_x: |x| of the largest lateral deflection, over r (0: a buckle in the middle of
    the span, as a quasi-static feed gives; ~0.6: buckles next to the channels);
  - half_waves: how many times y changes sign where |y| > 3 d, plus one;
  - central: the largest deflection over |x| < r/2 over the largest anywhere (1: the
    middle of the span buckled; small: only the wire next to the channels did);
  - Pi = v 2r / (pi^2 sqrt(k2 l0 / m)): the wire fed during the relaxation time of the
    span's lowest bending mode, over the span. A feed is quasi-static when Pi << 1.
Writes <out>.csv and a PNG of the buckled wires. A study, not a test.

A command-line entry point over workflows/first_buckle.smk: one job per (f, speed),
resumable (a run cut short continues from its checkpoint, a finished one is not run
again), locally on --cores or on Slurm with --profile slurm; the runs stay under --results.
The functions below measure and draw; the workflow imports them.

  /usr/bin/python3 scripts/first_buckle.py [--f 50 100] [--speeds 0.08 0.02 0.005] [--set drag_factor=1]
"""
import argparse
import csv
import math
import os
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import workflow_cli  # noqa: E402

K2, L0, M = 60.0, 1.0, 1.0  # examples/crumple2d/lib/scene.lua


def span_number(f, v):
    return v * 2 * f / (math.pi ** 2 * math.sqrt(K2 * L0 / M))


def measure(x, y, r):
    """Peak position over r, amplitude, half-waves and central share of a wire along x."""
    inside = np.abs(x) < r - 1
    xa, ya = x[inside], y[inside]
    k = int(np.argmax(np.abs(ya)))
    s = np.sign(ya[np.abs(ya) > 3.0])
    half_waves = int(np.sum(s[1:] != s[:-1])) + 1 if s.size else 0
    central = float(np.abs(ya[np.abs(xa) < r / 2]).max() / max(np.abs(ya).max(), 1e-300))
    return abs(xa[k]) / r, float(np.abs(ya).max()), half_waves, central


def point_variables(f, v, feed, seed):
    """The deck variables of one point: the run stops (max_phi) once `feed` cavity radii of
    wire have entered per channel (phi counts the wire inside the cavity, fix inject/wire:
    the straight start spans 2r)."""
    length = 2 * f + 2 * feed * f
    return {"f": f, "s": v, "seed": seed, "max_phi": length / (math.pi * f * f)}


def wire_measures(pos, r):
    """The measures of a buckled wire (its nodes in chain order) in a cavity of radius r."""
    peak_x, amp, hw, central = measure(pos[:, 0], pos[:, 1], r)
    return {"peak_x_over_r": peak_x, "amplitude": amp, "half_waves": hw, "central": central}


def study_row(f, v, seed, record):
    """A row of the table from a point's run record (the workflow's JSON)."""
    row = {"f": f, "speed": v, "seed": seed, "Pi": span_number(f, v), "status": "ok"}
    measures = record.get("measures") or {}
    if record["status"] != "ok" or not measures:
        row.update(status="failed", error=(record.get("error") or "no final state")[:200])
        return row
    row["steps"] = int(float(record["result"]["steps"]))
    row.update(measures)
    return row


KEYS = ["f", "speed", "seed", "Pi", "steps", "peak_x_over_r", "amplitude", "half_waves", "central",
        "status", "error"]


def write_outputs(results, out, deck, feed):
    """<out>.csv (a row per point) and <out>.png (the buckled wires, a row per f and a
    column per speed) from (row, positions or None) pairs."""
    results = sorted(results, key=lambda rp: (rp[0]["f"], -rp[0]["speed"]))
    rows = [r for r, _ in results]
    with open(out + ".csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=KEYS, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fs = sorted({r["f"] for r in rows})
    speeds = sorted({r["speed"] for r in rows}, reverse=True)
    fig, axes = plt.subplots(len(fs), len(speeds), figsize=(3.2 * len(speeds), 2.2 * len(fs) + 0.6),
                             squeeze=False)
    for r, xy in results:
        ax = axes[fs.index(r["f"])][speeds.index(r["speed"])]
        ax.set_title(f"f = {r['f']:g}, v = {r['speed']:g}, Pi = {r['Pi']:.3f}", fontsize=9)
        t = np.linspace(0, 2 * np.pi, 200)
        ax.plot(r["f"] * np.cos(t), r["f"] * np.sin(t), color="0.6", lw=0.8)
        if xy is not None:
            ax.plot(xy[:, 0], xy[:, 1], color="k", lw=1.2)
        ax.set_aspect("equal")
        ax.set_ylim(-0.6 * r["f"], 0.6 * r["f"])
        ax.set_xticks([])
        ax.set_yticks([])
    fig.suptitle(f"{deck}: the wire after {feed:g} r fed per channel", fontsize=10)
    fig.tight_layout()
    fig.savefig(out + ".png", dpi=110)
    plt.close(fig)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--slender", default=os.path.join(ROOT, "build", "slender"))
    ap.add_argument("--deck", default="classic")
    ap.add_argument("--f", type=float, nargs="+", default=[50, 100])
    ap.add_argument("--speeds", type=float, nargs="+", default=[0.08, 0.02, 0.005])
    ap.add_argument("--feed", type=float, default=0.2, help="wire fed per channel, in cavity radii")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--set", nargs="*", default=[], metavar="NAME=VALUE",
                    help="deck variables fixed for every run (-v NAME=VALUE), e.g. drag_factor=1")
    ap.add_argument("--results", default=None,
                    help="the workflow's results folder (default results/first_buckle_<deck>); "
                         "runs already there are not run again")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "crumple2d", "first_buckle"))
    workflow_cli.add_options(ap, max(1, os.cpu_count() or 2))
    a = ap.parse_args(argv)
    a.results = os.path.abspath(a.results or os.path.join(ROOT, "results", f"first_buckle_{a.deck}"))
    lists = workflow_cli.yaml_list
    cfg = [f"slender={os.path.abspath(a.slender)}", f"results={a.results}", f"deck={a.deck}",
           f"f={lists(a.f)}", f"speeds={lists(a.speeds)}", f"feed={a.feed:g}", f"seed={a.seed}"]
    if a.set:
        cfg.append("vars=" + workflow_cli.yaml_vars(a.set))
    done = workflow_cli.run("first_buckle", cfg, a)
    if a.dry_run or done != 0:
        return done
    workflow_cli.copy_outputs(os.path.join(a.results, "first_buckle"), a.out, (".csv", ".png"))
    with open(a.out + ".csv") as fh:
        rows = list(csv.DictReader(fh))
    for r in rows:
        head = f"f = {float(r['f']):g}, v = {float(r['speed']):g}"
        if r["status"] != "ok":
            print(f"{head}: failed: {r.get('error')}")
            continue
        print(f"{head}: Pi = {float(r['Pi']):.3f}, peak at |x|/r = {float(r['peak_x_over_r']):.2f}, "
              f"amplitude {float(r['amplitude']):.1f} d, {r['half_waves']} half-waves, "
              f"central share {float(r['central']):.2f}, {r['steps']} steps")
    print("wrote", a.out + ".csv", a.out + ".png")
    return 0 if all(r["status"] == "ok" for r in rows) else 1


if __name__ == "__main__":
    raise SystemExit(main())

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

  /usr/bin/python3 scripts/first_buckle.py [--f 50 100] [--speeds 0.08 0.02 0.005]
"""
import argparse
import concurrent.futures as cf
import csv
import math
import os
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))
from slender.io import Trajectory  # noqa: E402
from slender.run import run_deck  # noqa: E402
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


def run(binary, examples, deck, f, v, feed, seed):
    # phi counts the wire inside the cavity (fix inject/wire): the straight start spans 2r
    length = 2 * f + 2 * feed * f
    max_phi = length / (math.pi * f * f)
    # no periodic frames: the dump writes the state the run stops in
    variables = [f"f={f}", f"s={v}", f"seed={seed}", f"max_phi={max_phi}", "dump_every=1000000000000"]
    with tempfile.TemporaryDirectory() as tmp:
        res = run_deck(os.path.join(examples, "crumple2d", deck + ".lua"), variables, cwd=tmp, binary=binary)
        row = {"f": f, "speed": v, "seed": seed, "Pi": span_number(f, v), "status": "ok"}
        if res.returncode != 0:
            row.update(status="failed", error=(res.error or "?")[:200])
            return row, None
        with Trajectory(os.path.join(tmp, deck + ".h5")) as t:
            chains, step = t.frame(-1), int(t.steps[-1])
    assert len(chains) == 1, f"one open wire expected, found {len(chains)} pieces"
    pos = chains[0]
    peak_x, amp, hw, central = measure(pos[:, 0], pos[:, 1], f)
    row.update(steps=step, peak_x_over_r=peak_x, amplitude=amp, half_waves=hw, central=central)
    return row, pos[:, :2]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--slender", default=os.path.join(ROOT, "build", "slender"))
    ap.add_argument("--examples", default=os.path.join(ROOT, "examples"))
    ap.add_argument("--deck", default="classic")
    ap.add_argument("--f", type=float, nargs="+", default=[50, 100])
    ap.add_argument("--speeds", type=float, nargs="+", default=[0.08, 0.02, 0.005])
    ap.add_argument("--feed", type=float, default=0.2, help="wire fed per channel, in cavity radii")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "crumple2d", "first_buckle"))
    a = ap.parse_args()
    a.slender, a.examples = os.path.abspath(a.slender), os.path.abspath(a.examples)
    cases = [(f, v) for f in a.f for v in a.speeds]
    with cf.ThreadPoolExecutor(a.jobs) as ex:
        results = list(ex.map(lambda c: run(a.slender, a.examples, a.deck, c[0], c[1], a.feed, a.seed),
                              cases))
    rows = [r for r, _ in results]
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    keys = ["f", "speed", "seed", "Pi", "steps", "peak_x_over_r", "amplitude", "half_waves", "central",
            "status", "error"]
    with open(a.out + ".csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=keys, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    for r in rows:
        if r["status"] != "ok":
            print(f"f = {r['f']:g}, v = {r['speed']:g}: failed: {r.get('error')}")
            continue
        print(f"f = {r['f']:g}, v = {r['speed']:g}: Pi = {r['Pi']:.3f}, peak at |x|/r = "
              f"{r['peak_x_over_r']:.2f}, amplitude {r['amplitude']:.1f} d, {r['half_waves']} half-waves, "
              f"central share {r['central']:.2f}, {r['steps']} steps")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fs = sorted(set(a.f))
    fig, axes = plt.subplots(len(fs), len(a.speeds), figsize=(3.2 * len(a.speeds), 2.2 * len(fs) + 0.6),
                             squeeze=False)
    for (r, xy), ax in zip(results, [ax for row in axes for ax in row]):
        ax.set_title(f"f = {r['f']:g}, v = {r['speed']:g}, Pi = {r['Pi']:.3f}", fontsize=9)
        t = np.linspace(0, 2 * np.pi, 200)
        ax.plot(r["f"] * np.cos(t), r["f"] * np.sin(t), color="0.6", lw=0.8)
        if xy is not None:
            ax.plot(xy[:, 0], xy[:, 1], color="k", lw=1.2)
        ax.set_aspect("equal")
        ax.set_ylim(-0.6 * r["f"], 0.6 * r["f"])
        ax.set_xticks([])
        ax.set_yticks([])
    fig.suptitle(f"{a.deck}: the wire after {a.feed:g} r fed per channel", fontsize=10)
    fig.tight_layout()
    fig.savefig(a.out + ".png", dpi=110)
    print("wrote", a.out + ".csv", a.out + ".png")
    return 0 if all(r["status"] == "ok" for r in rows) else 1


if __name__ == "__main__":
    raise SystemExit(main())

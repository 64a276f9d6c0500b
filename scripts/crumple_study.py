#!/usr/bin/env python3
"""How the morphology of a crumpling deck depends on one of its choices: a deck variable
(-v NAME=VALUE) taking several values, e.g. the hardening slope K_h/K_e of the bending law
(docs/models.md §2.2), the drag factor or the kind of damping (docs/crumple2d/causes.md).
Runs the deck for each value and seed until max_phi (or to the jam), and measures the final
wire:
  - ab_ratio, winding, loops, contacts: as the deck reports them (docs/models.md §2.7);
  - wall_contacts: wire-wall contacts at the end (cavity.contacts);
  - outer_share: the share of the wire inside the cavity that lies beyond 0.7 r (the outer
    ring holds 51 % of the area; loop cascades along the wall fill it, folds along the feed
    axis leave it empty);
  - half_width: the 90th percentile of |y| / r over the wire inside the cavity (how far the
    packing reaches away from the feed axis).
Writes <out>.csv, <out>.md and a PNG of the final wires (a row per seed, a column per
ratio). A study, not a test.

  /usr/bin/python3 scripts/crumple_study.py --variable drag_factor --values 1 0.1 0.01 \
      [--f 25] [--seeds 1 2 3 4] [--max-phi 0.2 | --jam] [--set damping=relative] [--jobs 2]
  (scripts/hardening_study.py: the same with --variable hardening)
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

RESULT_KEYS = ("phi", "jammed", "ab_ratio", "winding", "loops", "contacts", "wall_contacts", "steps",
               "wall_s", "s")


def shape_measures(pos, r):
    """outer_share and half_width of the wire nodes strictly inside the cavity."""
    rad = np.hypot(pos[:, 0], pos[:, 1])
    inside = rad < r - 0.5
    return float(np.mean(rad[inside] > 0.7 * r)), float(np.percentile(np.abs(pos[inside, 1]), 90) / r)


def study_row(result, f, value, seed):
    """A row of the study's table from a run's RESULT (a dict of its fields), before the
    shape measures."""
    row = {"f": f, "value": value, "seed": seed, "status": "ok"}
    row.update({k: float(v) for k, v in result.items() if k in RESULT_KEYS})
    return row


def run(binary, examples, deck, f, variable, value, seed, max_phi, speed, fixed=()):
    # no periodic frames: the dump writes the state the run stops in
    variables = [f"f={f}", f"{variable}={value}", f"seed={seed}", f"max_phi={max_phi}",
                 "dump_every=1000000000000", "thermo_every=10000", *fixed]
    if speed is not None:
        variables.append(f"s={speed}")
    with tempfile.TemporaryDirectory() as tmp:
        res = run_deck(os.path.join(examples, "crumple2d", deck + ".lua"), variables, cwd=tmp, binary=binary)
        row = study_row(res.result, f, value, seed)
        if res.returncode != 0 or "phi" not in row:
            row.update(status="failed", error=(res.error or "?")[:200])
            return row, None
        with Trajectory(os.path.join(tmp, deck + ".h5")) as t:
            chains = t.frame(-1)
    # in chain order (injected nodes are appended to the arrays)
    pos = chains[0] if len(chains) == 1 else np.concatenate(chains)
    row["outer_share"], row["half_width"] = shape_measures(pos, f)
    return row, pos


KEYS = ["f", "s", "value", "seed", "phi", "jammed", "ab_ratio", "winding", "loops", "contacts",
        "wall_contacts", "outer_share", "half_width", "steps", "wall_s", "status", "error"]


def value_text(v):
    return f"{v:g}" if isinstance(v, float) else str(v)


def write_tables(rows, out, title, label, writer="scripts/crumple_study.py"):
    with open(out + ".csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=KEYS, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    with open(out + ".md", "w") as fh:
        fh.write(f"# {title}\n\nWritten by `{writer}`. A/B < 0.5 is classic by the docs/models.md "
                 "§2.7 criterion; outer share = wire beyond 0.7 r; half width = 90th percentile of |y|/r.\n\n")
        fh.write(f"| {label} | seed | phi | jammed | A/B | winding | loops | contacts | wall contacts | "
                 "outer share | half width | steps | wall s |\n|" + "---|" * 13 + "\n")
        for r in rows:
            if r["status"] != "ok":
                fh.write(f"| {value_text(r['value'])} | {r['seed']} | failed: {r.get('error')} |" + " |" * 10 + "\n")
                continue
            fh.write(f"| {value_text(r['value'])} | {r['seed']} | {r['phi']:.4f} | {int(r['jammed'])} | "
                     f"{r['ab_ratio']:.2f} | {r['winding']:.2f} | {int(r['loops'])} | {int(r['contacts'])} | "
                     f"{int(r['wall_contacts'])} | {r['outer_share']:.2f} | {r['half_width']:.2f} | "
                     f"{int(r['steps'])} | {r['wall_s']:.0f} |\n")


def plot(results, values, seeds, out, title, label):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(len(seeds), len(values), figsize=(2.6 * len(values), 2.7 * len(seeds) + 0.5),
                             squeeze=False)
    t = np.linspace(0, 2 * np.pi, 200)
    for (r, xy), ax in zip(results, [ax for row in axes for ax in row]):
        ax.plot(r["f"] * np.cos(t), r["f"] * np.sin(t), color="0.6", lw=0.8)
        if xy is not None:
            ax.plot(xy[:, 0], xy[:, 1], color="k", lw=0.8)
            ax.set_title(f"{label} = {value_text(r['value'])}, seed {r['seed']}\nA/B {r['ab_ratio']:.2f}, "
                         f"outer {r['outer_share']:.2f}", fontsize=8)
        ax.set_aspect("equal")
        ax.set_xticks([])
        ax.set_yticks([])
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(out + ".png", dpi=110)


def parse_value(text):
    try:
        return float(text)
    except ValueError:
        return text


def main(argv=None, variable=None, label=None, default_out=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--slender", default=os.path.join(ROOT, "build", "slender"))
    ap.add_argument("--examples", default=os.path.join(ROOT, "examples"))
    ap.add_argument("--deck", default="classic")
    ap.add_argument("--f", type=float, default=25)
    if variable is None:
        ap.add_argument("--variable", required=True, help="the deck variable varied (-v NAME=VALUE)")
        ap.add_argument("--label", default=None, help="its name in tables and plots (default: the variable)")
    ap.add_argument("--values", "--ratios", nargs="+", default=None, required=variable is None,
                    help="its values (--ratios: the hardening study's name)")
    ap.add_argument("--set", nargs="*", default=[], metavar="NAME=VALUE",
                    help="other deck variables, the same in every run")
    ap.add_argument("--seeds", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--max-phi", type=float, default=0.2)
    ap.add_argument("--jam", action="store_true", help="run to the jam (max_phi = 1)")
    ap.add_argument("--speed", type=float, default=None, help="feed speed (default: the deck's s)")
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--out", default=default_out)
    a = ap.parse_args(argv)
    if variable is None:
        variable, label = a.variable, a.label or a.variable
    if a.out is None:
        ap.error("--out is required")
    values = [parse_value(v) for v in (a.values or ["0.05", "0.1", "0.2", "0.4", "0.8"])]
    a.slender, a.examples = os.path.abspath(a.slender), os.path.abspath(a.examples)
    max_phi = 1.0 if a.jam else a.max_phi
    cases = [(v, s) for s in a.seeds for v in values]
    with cf.ThreadPoolExecutor(a.jobs) as ex:
        results = list(ex.map(lambda c: run(a.slender, a.examples, a.deck, a.f, variable, c[0], c[1], max_phi,
                                            a.speed, a.set), cases))
    rows = [r for r, _ in results]
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    stop = "to the jam" if a.jam else f"to phi = {max_phi:g}"
    fixed = f" ({', '.join(a.set)})" if a.set else ""
    title = f"{a.deck}, f = {a.f:g}{fixed}, {stop}: the wire against {label}"
    write_tables(rows, a.out, title, label)
    plot(results, values, a.seeds, a.out, title, label)
    for r in rows:
        head = f"{label} = {value_text(r['value'])}, seed {r['seed']}"
        if r["status"] != "ok":
            print(f"{head}: failed: {r.get('error')}")
            continue
        print(f"{head}: phi {r['phi']:.4f} (jammed {int(r['jammed'])}), A/B {r['ab_ratio']:.2f}, "
              f"outer share {r['outer_share']:.2f}, half width {r['half_width']:.2f}, "
              f"wall contacts {int(r['wall_contacts'])}, {r['wall_s']:.0f} s")
    print("wrote", a.out + ".csv", a.out + ".md", a.out + ".png")
    return 0 if all(r["status"] == "ok" for r in rows) else 1


if __name__ == "__main__":
    raise SystemExit(main())

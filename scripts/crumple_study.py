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
value). A study, not a test.

A command-line entry point over workflows/crumple_study.smk: one job per (value, seed),
resumable from checkpoints (a run a sitting cuts short continues on the next call, a
finished one is not run again), locally on --cores or on Slurm with --profile slurm. Its
results stay under --results; the table and picture are copied to --out. The functions
below measure and draw; the workflow imports them.

  /usr/bin/python3 scripts/crumple_study.py --variable drag_factor --values 1 0.1 0.01 \
      [--f 25] [--seeds 1 2 3 4] [--max-phi 0.2 | --jam] [--set damping=relative] [--cores 2]
  (scripts/hardening_study.py: the same with --variable hardening)
"""
import argparse
import csv
import os
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import causes_table  # noqa: E402
import workflow_cli  # noqa: E402

RESULT_KEYS = ("phi", "force", "jammed", "ab_ratio", "winding", "loops", "contacts", "wall_contacts", "steps",
               "wall_s", "s", "fractal_dimension")


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


KEYS = ["f", "s", "value", "seed", "phi", "force", "jammed", "ab_ratio", "winding", "loops", "contacts",
        "wall_contacts", "outer_share", "half_width", "fractal_dimension", "steps", "wall_s", "status", "error"]

# the columns of the per-value summary (mean +- standard error over the seeds that ran)
SUMMARY = [("phi", "phi", 3), ("loops", "loops", 1), ("contacts", "contacts", 0), ("outer_share", "outer share", 2),
           ("fractal_dimension", "D", 3), ("wall_s", "wall s", 0)]


def summary_rows(rows):
    """Per value, in order of appearance: (value, seeds, {key: values}) over the rows that ran; a key
    that no run reported (D from a deck without compute fractal2d) is left out."""
    out = []
    for v in dict.fromkeys(r["value"] for r in rows):
        ok = [r for r in rows if r["value"] == v and r["status"] == "ok"]
        if not ok:
            continue
        values = {k: [float(r[k]) for r in ok] for k, _, _ in SUMMARY if all(k in r for r in ok)}
        out.append((v, len(ok), values))
    return out


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
        summary = summary_rows(rows)
        if summary:
            cols = [(k, name, digits) for k, name, digits in SUMMARY if any(k in st for _, _, st in summary)]
            fh.write(f"\nMean ± standard error over the seeds:\n\n| {label} | seeds | "
                     + " | ".join(name for _, name, _ in cols) + " |\n|" + "---|" * (len(cols) + 2) + "\n")
            for v, n, st in summary:
                cells = [causes_table.mean_se(st.get(k, []), d) for k, _, d in cols]
                fh.write(f"| {value_text(v)} | {n} | " + " | ".join(cells) + " |\n")


def plot(results, values, seeds, out, title, label):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    # a row per seed and a column per value; a single value is wrapped into a square-ish grid
    ncol = len(values) if len(values) > 1 else int(np.ceil(np.sqrt(len(seeds))))
    nrow = int(np.ceil(len(results) / ncol))
    fig, axes = plt.subplots(nrow, ncol, figsize=(2.6 * ncol, 2.7 * nrow + 0.5), squeeze=False)
    t = np.linspace(0, 2 * np.pi, 200)
    for (r, xy), ax in zip(results, [ax for row in axes for ax in row]):
        ax.plot(r["f"] * np.cos(t), r["f"] * np.sin(t), color="0.6", lw=0.8)
        if xy is not None:
            ax.plot(xy[:, 0], xy[:, 1], color="k", lw=0.8)
            d = f", D {r['fractal_dimension']:.3f}" if "fractal_dimension" in r else ""
            ax.set_title(f"{label} = {value_text(r['value'])}, seed {r['seed']}\nA/B {r['ab_ratio']:.2f}, "
                         f"outer {r['outer_share']:.2f}{d}", fontsize=8)
        ax.set_aspect("equal")
        ax.set_xticks([])
        ax.set_yticks([])
    for ax in [ax for row in axes for ax in row][len(results):]:
        ax.set_visible(False)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(out + ".png", dpi=110)


def parse_value(text):
    try:
        return float(text)
    except ValueError:
        return text


def config_args(a, variable, label, max_phi):
    """The workflow's --config of these arguments."""
    fixed = list(a.set) + ([f"s={a.speed:g}"] if a.speed is not None else [])
    cfg = [f"slender={os.path.abspath(a.slender)}", f"results={a.results}", f"deck={a.deck}",
           f"f={a.f:g}", f"variable={variable}", f"label='{label}'",
           "values=" + workflow_cli.yaml_list([parse_value(v) for v in a.values]),
           "seeds=" + workflow_cli.yaml_list(a.seeds), f"max_phi={max_phi:g}",
           "set=" + workflow_cli.yaml_vars(fixed), f"checkpoint_every={a.checkpoint_every}"]
    if a.timeout:
        cfg.append(f"timeout={a.timeout:g}")
    return cfg


def main(argv=None, variable=None, label=None, default_out=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--slender", default=os.path.join(ROOT, "build", "slender"))
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
    ap.add_argument("--timeout", type=float, default=None, help="seconds per run (a cut run continues next time)")
    ap.add_argument("--checkpoint-every", type=int, default=1000000, help="steps between a run's checkpoints")
    ap.add_argument("--results", default=None,
                    help="the workflow's results folder (default results/crumple_study_<deck>_f<f>_<variable> "
                         "in the repository); runs already there are not run again")
    ap.add_argument("--out", default=default_out)
    workflow_cli.add_options(ap, max(1, os.cpu_count() or 2))
    a = ap.parse_args(argv)
    if variable is None:
        variable, label = a.variable, a.label or a.variable
    if a.out is None:
        ap.error("--out is required")
    a.values = a.values or ["0.05", "0.1", "0.2", "0.4", "0.8"]
    max_phi = 1.0 if a.jam else a.max_phi
    stem = f"{a.deck}_f{a.f:g}_{variable}"
    a.results = os.path.abspath(a.results or os.path.join(ROOT, "results", "crumple_study_" + stem))
    done = workflow_cli.run("crumple_study", config_args(a, variable, label, max_phi), a)
    if a.dry_run or done != 0:
        return done
    workflow_cli.copy_outputs(os.path.join(a.results, stem), a.out, (".csv", ".md", ".png"))
    with open(a.out + ".csv") as fh:
        rows = list(csv.DictReader(fh))
    for r in rows:
        head = f"{label} = {r['value']}, seed {r['seed']}"
        if r["status"] != "ok":
            print(f"{head}: {r['status']}: {r.get('error')}")
            continue
        print(f"{head}: phi {float(r['phi']):.4f} (jammed {int(float(r['jammed']))}), A/B {float(r['ab_ratio']):.2f}, "
              f"outer share {float(r['outer_share']):.2f}, half width {float(r['half_width']):.2f}, "
              f"wall contacts {int(float(r['wall_contacts']))}, {float(r['wall_s']):.0f} s")
    print("wrote", a.out + ".csv", a.out + ".md", a.out + ".png")
    return 0 if all(r["status"] == "ok" for r in rows) else 1


if __name__ == "__main__":
    raise SystemExit(main())

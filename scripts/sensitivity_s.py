#!/usr/bin/env python3
"""Sensitivity of the 2D crumpling results to the thesis' undefined parameter s
(docs/models.md §2.6): reading (a) s = injection speed (with K_h = 0.05 K_e), reading (b)
s = hardening ratio K_h/K_e (with a fixed feed speed). Runs a crumpling deck to jamming for
each value under each reading and writes a CSV and a Markdown table of the jamming
density, injection force, contacts and the morphology indicators. A study, not a test.

A command-line entry point over workflows/crumple_study.smk, run once per reading (the
varied deck variable is s, then hardening): one job per run, resumable, locally on
--cores or on Slurm with --profile slurm; the runs stay under --results.

  /usr/bin/python3 scripts/sensitivity_s.py [--deck classic] [--f 10] [--values 0.04 0.06 0.08]
"""
import argparse
import csv
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import workflow_cli  # noqa: E402

ROOT = workflow_cli.ROOT
KEYS = ["reading", "s_value", "s", "seed", "phi", "force", "jammed", "contacts", "ab_ratio", "winding", "loops",
        "steps", "wall_s", "status", "error"]


def reading_config(a, reading):
    """The crumple_study workflow's --config of one reading, and the stem of its outputs."""
    variable, fixed = ("s", "{hardening: 0.05}") if reading == "a" else ("hardening", f"{{s: {a.speed_b:g}}}")
    cfg = [f"slender={os.path.abspath(a.slender)}", f"results={a.results}/{reading}", f"deck={a.deck}",
           f"f={a.f:g}", f"variable={variable}", "values=" + workflow_cli.yaml_list(a.values),
           "seeds=" + workflow_cli.yaml_list(a.seeds), "max_phi=1", f"set={fixed}",
           f"checkpoint_every={a.checkpoint_every}"]
    return cfg, os.path.join(a.results, reading, f"{a.deck}_f{a.f:g}_{variable}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--slender", default=os.path.join(ROOT, "build", "slender"))
    ap.add_argument("--deck", default="classic")
    ap.add_argument("--f", type=float, default=10)
    ap.add_argument("--values", type=float, nargs="+", default=[0.04, 0.06, 0.08])
    ap.add_argument("--speed-b", type=float, default=0.05, help="feed speed under reading (b)")
    ap.add_argument("--seeds", type=int, nargs="+", default=[1])
    ap.add_argument("--checkpoint-every", type=int, default=1000000, help="steps between a run's checkpoints")
    ap.add_argument("--results", default=None,
                    help="the workflow's results folder (default results/s_sensitivity_<deck>_f<f>)")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "crumple2d"))
    workflow_cli.add_options(ap, max(1, os.cpu_count() or 2))
    a = ap.parse_args(argv)
    stem_name = f"s_sensitivity_{a.deck}_f{a.f:g}"
    a.results = os.path.abspath(a.results or os.path.join(ROOT, "results", stem_name))
    rows = []
    for reading in ("a", "b"):
        cfg, made = reading_config(a, reading)
        done = workflow_cli.run("crumple_study", cfg, a)
        if a.dry_run or done != 0:
            if done != 0:
                return done
            continue
        with open(made + ".csv") as fh:
            for r in csv.DictReader(fh):
                rows.append({**r, "reading": reading, "s_value": r["value"]})
    if a.dry_run:
        return 0
    os.makedirs(a.out, exist_ok=True)
    stem = os.path.join(a.out, stem_name)
    with open(stem + ".csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=KEYS, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)

    def num(r, key, spec):
        try:
            return format(float(r[key]), spec)
        except (KeyError, TypeError, ValueError):
            return "-"
    with open(stem + ".md", "w") as fh:
        fh.write(f"# Sensitivity to s: {a.deck}, f = {a.f:g}, seeds {a.seeds}\n\n")
        fh.write("Written by `scripts/sensitivity_s.py`. (a): s is the feed speed, K_h = 0.05 K_e. "
                 f"(b): s is K_h / K_e, feed speed {a.speed_b:g}.\n\n")
        fh.write("| reading | s | seed | jamming phi | force | contacts | A/B | winding | steps | wall s | status |\n")
        fh.write("|---|---|---|---|---|---|---|---|---|---|---|\n")
        for r in rows:
            status = r["status"] + (": " + r["error"] if r.get("error") else "")
            fh.write(f"| {r['reading']} | {r['s_value']} | {r['seed']} | {num(r, 'phi', '.4f')} | "
                     f"{num(r, 'force', '.4g')} | {num(r, 'contacts', '.0f')} | {num(r, 'ab_ratio', '.3f')} | "
                     f"{num(r, 'winding', '.3f')} | {num(r, 'steps', '.0f')} | {num(r, 'wall_s', '.1f')} | "
                     f"{status} |\n")
    print(open(stem + ".md").read())
    print("wrote", stem + ".csv", stem + ".md")
    return 0 if rows and all(r["status"] == "ok" for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())

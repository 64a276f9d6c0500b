#!/usr/bin/env python3
"""Does the answer depend on the time step? Runs one injection deck (2D crumpling or 3D
packing) to its jam over a ladder of (integrator, dt) rungs with several seeds, and writes
the science observables next to the wall time each rung cost (work-precision style):
a command-line entry point over workflows/dt_ladder.smk (one job per run and seed,
resumable, only missing runs run; --profile slurm for a cluster).

  - 2D: phi_jam, the injection force at the stop, A/B, loops, contacts, fractal dimension;
  - 3D: phi_max, the force, E_b R / YI, contacts.

The first rung is the reference (the smallest step); a rung agrees with it when the
difference of the seed means lies within the seed scatter (the larger of the two standard
errors, times 2). Writes <out>.csv (one row per run), <out>.md (a row per rung) and
<out>.png (each observable against wall time). A study, not a test.

  /usr/bin/python3 scripts/dt_ladder.py --deck crumple2d/classic --var f=25 \
      --rung gear:0.000316 --rung verlet:auto --seeds 1 2 3 4 --out docs/crumple2d/dt_ladder_f25
"""
import argparse
import csv
import math
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))
import slender.run as slender_run  # noqa: E402
import workflow_cli  # noqa: E402

OBSERVABLES = {
    "crumple2d": ["phi", "force", "ab_ratio", "loops", "contacts", "fractal_dimension"],
    "pack3d": ["phi", "force_R2_over_YI", "bend_R_over_YI", "contacts"],
}


def run_deck(binary, deck_path, variables, threads=1):
    """Runs a deck with output=false, the `-v` variables and `threads` threads in a scratch
    folder; returns its RESULT fields (numbers as floats) with status ok/failed (and the last
    error line)."""
    res = slender_run.run_deck(deck_path, ["output=false"] + variables, threads=threads, binary=binary)
    row = {k: float(v) if isinstance(v, (int, float)) else v for k, v in res.result.items()}
    row["status"] = "ok" if res.returncode == 0 and "phi" in row else "failed"
    if row["status"] != "ok":
        row["error"] = (res.error or "?")[:300]
    return row


def run(binary, examples, deck, variables, rung, seed):
    integrator, dt, *extra = rung.split(":")
    row = {"rung": rung, "integrator": integrator, "dt": dt, "seed": seed}
    row.update(run_deck(binary, os.path.join(examples, deck + ".lua"),
                        [f"integrator={integrator}", f"dt={dt}", f"seed={seed}"] + variables + extra))
    return row


def stats(values):
    v = [x for x in values if isinstance(x, float) and math.isfinite(x)]
    if not v:
        return math.nan, math.nan
    mean = sum(v) / len(v)
    if len(v) < 2:
        return mean, math.nan
    var = sum((x - mean) ** 2 for x in v) / (len(v) - 1)
    return mean, math.sqrt(var / len(v))


def rung_name(rung):
    """A rung as a file name (integrator:dt:var=value -> integrator_dt_var-value)."""
    return rung.replace(":", "_").replace("=", "-").replace("/", "|")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--deck", required=True, help="crumple2d/classic, pack3d/low_torsion, ...")
    ap.add_argument("--var", action="append", default=[], help="a deck variable, e.g. f=25")
    ap.add_argument("--rung", action="append", required=True,
                    help="integrator:dt[:var=value...] (dt a number or auto), e.g. "
                         "verlet:auto:adaptive=false; the first is the reference")
    ap.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3, 4])
    ap.add_argument("--slender", default=os.path.join(ROOT, "build", "slender"))
    ap.add_argument("--results", default=None,
                    help="the workflow's results folder (default results/dt_ladder/<out's name>); "
                         "runs already there are not run again")
    workflow_cli.add_options(ap, 2)
    ap.add_argument("--out", required=True, help="output path without extension")
    a = ap.parse_args()
    results = os.path.abspath(a.results or os.path.join(ROOT, "results", "dt_ladder", os.path.basename(a.out)))
    cfg = [f"slender={os.path.abspath(a.slender)}", f"results={results}", f"deck={a.deck}",
           f"rungs={workflow_cli.yaml_list(a.rung)}", f"seeds={workflow_cli.yaml_list(a.seeds)}",
           f"vars={workflow_cli.yaml_vars(a.var)}"]
    done = workflow_cli.run("dt_ladder", cfg, a)
    if a.dry_run or done != 0:
        return done
    workflow_cli.copy_outputs(os.path.join(results, "dt_ladder"), a.out, (".csv", ".md", ".png"))
    print("wrote", a.out + ".csv", a.out + ".md", a.out + ".png")
    return 0


def write_outputs(rows, rungs, seeds, deck, variables, out):
    """<out>.csv (a row per run, in rung and seed order), <out>.md (a row per rung: seed
    means against the first rung) and <out>.png (each observable against wall time)."""
    obs = OBSERVABLES[deck.split("/")[0]]
    order = {r: k for k, r in enumerate(rungs)}
    rows = sorted(rows, key=lambda r: (order[r["rung"]], r["seed"]))
    a = argparse.Namespace(out=out, deck=deck, var=variables, seeds=seeds)
    keys = ["rung", "integrator", "dt", "seed", "status", "steps", "wall_s", "nodes"] + obs + ["jammed", "error"]
    with open(a.out + ".csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=keys, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow(r)

    summary = []
    for rung in rungs:
        rs = [r for r in rows if r["rung"] == rung and r["status"] == "ok"]
        failed = sum(1 for r in rows if r["rung"] == rung) - len(rs)
        s = {"rung": rung, "runs": len(rs), "failed": failed,
             "wall_s": stats([float(r["wall_s"]) for r in rs])[0],
             "steps": stats([float(r["steps"]) for r in rs])[0]}
        for o in obs:
            s[o] = stats([r.get(o, math.nan) for r in rs])
        summary.append(s)
    ref = summary[0]
    with open(a.out + ".md", "w") as fh:
        fh.write(f"# Time-step ladder: {a.deck} {' '.join(a.var)}, seeds {a.seeds}\n\n")
        fh.write("Written by `workflows/dt_ladder.smk` (`scripts/dt_ladder.py`). Seed mean ± standard error per rung; the first "
                 "rung is the reference. A value marked * differs from the reference by more than "
                 "twice the larger standard error.\n\n")
        fh.write("| rung | runs (failed) | mean steps | mean wall s | " + " | ".join(obs) + " |\n")
        fh.write("|---|---|---|---|" + "---|" * len(obs) + "\n")
        for s in summary:
            cells = []
            for o in obs:
                m, e = s[o]
                rm, re = ref[o]
                tol = 2 * max(x for x in (e, re, 0.0) if math.isfinite(x))
                mark = "*" if s is not ref and math.isfinite(m) and abs(m - rm) > tol else ""
                cells.append(f"{m:.4g} ± {e:.2g}{mark}")
            fh.write(f"| {s['rung']} | {s['runs']} ({s['failed']}) | {s['steps']:.3g} | "
                     f"{s['wall_s']:.1f} | " + " | ".join(cells) + " |\n")
        bad = [r for r in rows if r["status"] != "ok"]
        if bad:
            fh.write("\nFailed runs:\n\n")
            for r in bad:
                fh.write(f"- {r['rung']} seed {r['seed']}: {r.get('error', '')}\n")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return
    fig, axes = plt.subplots(1, len(obs), figsize=(3.2 * len(obs), 3.0))
    for ax, o in zip(axes, obs):
        for k, s in enumerate(summary):
            rs = [r for r in rows if r["rung"] == s["rung"] and r["status"] == "ok"]
            ax.scatter([float(r["wall_s"]) for r in rs], [r.get(o, math.nan) for r in rs],
                       s=12, color=f"C{k}", alpha=0.5)
            m, e = s[o]
            ax.errorbar([s["wall_s"]], [m], yerr=[e if math.isfinite(e) else 0], fmt="o",
                        color=f"C{k}", label=s["rung"])
        ax.set_xscale("log")
        ax.set_xlabel("wall s per run")
        ax.set_title(o)
    axes[0].legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(a.out + ".png", dpi=110)




if __name__ == "__main__":
    sys.exit(main())

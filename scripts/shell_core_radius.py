#!/usr/bin/env python3
"""Core radius R_C of the e-cone against the thickness h (docs/models.md §6.11, §7.2 S-1):
runs examples/shells/econe.lua without self-contact up to phi_e (default 3, below the
first contact of every h) on a disc of outer edge `--edge` (default 1/8) whose core is
refined `level` times (refine_center = 0.3), for each h and level, and writes <out>.csv (one row per
run) and <out>.png: R_C(h) per
level with a power-law fit on the finest level, and R_C against the core edge (mesh
convergence). R_C is the energy criterion of compute core_radius; R_C_s (U_s below 10 %
of its peak) is logged next to it.

  /usr/bin/python3 scripts/shell_core_radius.py --h 0.04 0.02 0.01 0.005 --levels 2 3 4 5

A command-line entry point over workflows/shell_core_radius.smk (workflows/README.md): one
job per (h, level), resumable (a finished run is not run again), locally on --cores or on
Slurm with --profile slurm; the runs stay under --results, the table and picture are
copied to --out. run_one and plot are what the workflow runs and draws with.
"""
import argparse
import csv
import os
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))
from slender.run import run_deck  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import workflow_cli  # noqa: E402

FIELDS = ["h", "edge", "level", "core_edge", "phi_e", "R_C", "R_C_s", "Eb_hat", "E_s_over_E_b",
          "triangles", "fire_steps", "wall_s", "status", "error"]


def run_one(a, h, level):
    row = {"h": h, "edge": a.edge, "level": level, "core_edge": a.edge / 2 ** level, "phi_e": a.phi}
    with tempfile.TemporaryDirectory() as tmp:
        # FIRE, the relaxation the tables of docs/shells were measured with
        variables = ["fast=1", "minimizer=fire", f"h={h}", f"phi_max={a.phi}", "contact=0", "plots=0",
                     f"edge={a.edge}",
                     "refine_center=0.3", f"refine_levels={level}", f"out={tmp}/o"]
        run = run_deck(os.path.join(a.examples, "shells", "econe.lua"), variables, cwd=tmp, binary=a.slender)
        res = run.results_text[-1] if run.results_text else {}  # verbatim, as the deck printed it
        log = os.path.join(tmp, "o", "econe.csv")
        if run.returncode != 0 or not res or not os.path.exists(log):
            row["status"] = "failed"
            row["error"] = (run.error or "?")[:200].replace(",", ";")
            return row
        with open(log) as fh:
            last = list(csv.DictReader(fh))[-1]
        steps = sum(int(float(r["steps"])) for r in csv.DictReader(open(log)))
    row.update({"R_C": last["R_C"], "R_C_s": last["R_C_s"], "Eb_hat": last["Eb_hat"],
                "E_s_over_E_b": float(last["E_s"]) / float(last["E_b"]),
                "triangles": res["triangles"], "fire_steps": steps, "wall_s": res["wall_s"],
                "status": "ok"})
    return row


def plot(rows, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    ok = [r for r in rows if r["status"] == "ok"]
    if not ok:
        return
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    meshes = sorted({(float(r["edge"]), int(r["level"])) for r in ok}, key=lambda m: (-m[0], m[1]))
    fit = None
    for e, lv in meshes:
        rs = sorted((float(r["h"]), float(r["R_C"])) for r in ok
                    if (float(r["edge"]), int(r["level"])) == (e, lv))
        hs, rc = np.array(rs).T
        ax[0].loglog(hs, rc, "o-", label=f"edge 1/{round(1 / e)}, core 1/{round(2 ** lv / e)}")
        if (e, lv) == meshes[-1] and len(hs) >= 2:
            p, c = np.polyfit(np.log(hs), np.log(rc), 1)
            fit = (np.exp(c), p)
            hh = np.geomspace(hs.min(), hs.max(), 20)
            ax[0].loglog(hh, fit[0] * hh ** p, "k--", label=f"R_C = {fit[0]:.3g} h^{p:.2f}")
    ax[0].set_xlabel("h / R")
    ax[0].set_ylabel("R_C / R")
    ax[0].legend(fontsize=8)
    for hv in sorted({float(r["h"]) for r in ok}):
        for e in sorted({float(r["edge"]) for r in ok}, reverse=True):
            rs = sorted((float(r["core_edge"]), float(r["R_C"])) for r in ok
                        if float(r["h"]) == hv and float(r["edge"]) == e)
            if rs:
                ce, rc = np.array(rs).T
                ax[1].semilogx(ce, rc, "o-" if e >= 0.1 else "s--", label=f"h = {hv:g}, edge 1/{round(1 / e)}")
    ax[1].set_xlabel("core edge / R")
    ax[1].set_ylabel("R_C / R")
    ax[1].legend(fontsize=8)
    fig.suptitle(f"e-cone core radius at phi_e = {ok[0]['phi_e']} (energy criterion)")
    fig.tight_layout()
    fig.savefig(out + ".png", dpi=110)
    if fit:
        print(f"finest level: R_C = {fit[0]:.4g} h^{fit[1]:.3f}")
    print(f"wrote {out}.png")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--slender", default=os.path.join(ROOT, "build", "slender"))
    ap.add_argument("--h", type=float, nargs="+", default=[0.04, 0.02, 0.01, 0.005])
    ap.add_argument("--levels", type=int, nargs="+", default=[2, 3, 4, 5])
    ap.add_argument("--phi", type=float, default=3.0)
    ap.add_argument("--edge", type=float, default=0.125, help="outer edge of the disc mesh")
    ap.add_argument("--results", default=None,
                    help="the workflow's results folder (default results/shell_core_radius); runs "
                         "already there are not run again")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "shells", "core_radius"))
    workflow_cli.add_options(ap, max(1, os.cpu_count() or 2))
    a = ap.parse_args(argv)
    a.results = os.path.abspath(a.results or os.path.join(ROOT, "results", "shell_core_radius"))
    lists = workflow_cli.yaml_list
    cfg = [f"slender={os.path.abspath(a.slender)}", f"results={a.results}", "name=core_radius",
           f"h={lists(a.h)}", f"levels={lists(a.levels)}", f"edge={a.edge:g}", f"phi={a.phi:g}"]
    done = workflow_cli.run("shell_core_radius", cfg, a)
    if a.dry_run or done != 0:
        return done
    workflow_cli.copy_outputs(os.path.join(a.results, "core_radius"), a.out, (".csv", ".png"))
    with open(a.out + ".csv") as fh:
        rows = list(csv.DictReader(fh))
    for r in rows:
        print(f"h {r['h']} level {r['level']}: {r['status']} R_C {r.get('R_C')} wall {r.get('wall_s')} s")
    print(f"wrote {a.out}.csv, {a.out}.png")
    return 0 if rows and all(r["status"] == "ok" for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())

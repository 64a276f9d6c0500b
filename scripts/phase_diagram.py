#!/usr/bin/env python3
"""Morphological phase diagram of the 2D crumpled wire (W2-4, docs/models.md §7.2):
yield curvature kappa_theta x static friction mu_st, several seeds per point, each
run to jamming and classified (docs/models.md §2.7):

  spiral   winding of a half of the wire >= 2 turns and at most 2 loops
  classic  A/B < 0.5 (squared curvature concentrated near the wall)
  plastic  otherwise

Runs unattended and resumes: every finished run is appended to <out>.csv at once,
and a restart skips the (yield, mu, seed) already there (failed runs are retried
with --retry-failed). With --work DIR and --checkpoint-every N each run keeps a
checkpoint in DIR every N steps, and an interrupted run continues from it instead of
starting over (its wall time counts the parts up to their last checkpoint). Writes <out>.png (majority class per point, with its share)
and <out>_phi.png (mean jamming density).

  /usr/bin/python3 scripts/phase_diagram.py                      # the thesis' sweep, f = 50
  /usr/bin/python3 scripts/phase_diagram.py --work /scratch/pd50  # ... continuing cut runs
  /usr/bin/python3 scripts/phase_diagram.py --work /scratch/pd50 --settle  # before moving it
  /usr/bin/python3 scripts/phase_diagram.py --f 10 --yields 0 0.02 0.04 0.06 \\
      --mus 0 0.2 0.4 0.6 --seeds 1 --out docs/crumple2d/phase_diagram_f10
"""
import argparse
import concurrent.futures as cf
import csv
import os
import shutil
import json
import sys
import tempfile
import threading
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))
from slender.run import run_deck  # noqa: E402
FIELDS = ["f", "s", "yield", "mu", "seed", "class", "phi", "jammed", "loops", "winding", "ab_ratio",
          "contacts", "steps", "wall_s", "dt", "status", "error"]
DECK_DT = 0.01 * (1.0 / 1000.0) ** 0.5  # the scene's dt = 0.01 sqrt(m / k1)


def classify(row, min_winding=2.0, max_loops=2):
    if float(row["winding"]) >= min_winding and float(row["loops"]) <= max_loops:
        return "spiral"
    return "classic" if float(row["ab_ratio"]) < 0.5 else "plastic"


def run_one(a, y, mu, seed, unstable_before=False):
    """One run; a run the instability guard stopped is repeated once with half the
    time step (the guard's message names the step it would need). A point that a
    previous sweep found unstable starts at half the step."""
    if unstable_before and a.retry_dt:
        return run_once(a, y, mu, seed, 0.5 * DECK_DT)
    row = run_once(a, y, mu, seed, DECK_DT)
    if row["status"] in ("failed", "unstable") and "instability" in row.get("error", "") and a.retry_dt:
        first = row["error"]
        row = run_once(a, y, mu, seed, 0.5 * DECK_DT)
        if row["status"] != "ok":
            row["error"] = ("with dt/2: " + row.get("error", "") + " | with dt: " + first)[:300]
    return row


def run_once(a, y, mu, seed, dt):
    deck = os.path.join(a.examples, "crumple2d", "classic.lua")
    variables = [f"f={a.f}", f"s={a.s}", f"yield={y}", f"mu={mu}", f"seed={seed}", "output=false",
                 f"max_steps={a.max_steps}", f"dt={dt!r}"]
    if not a.work:
        res = run_deck(deck, variables, timeout=a.timeout, binary=a.slender)
        return parse_result(a, y, mu, seed, dt, res)
    # a kept run directory: continue from the run's last checkpoint, if any
    tmp = os.path.join(a.work, f"f{a.f:g}_s{a.s:g}_y{y:g}_mu{mu:g}_seed{seed}_dt{dt:.6g}")
    os.makedirs(tmp, exist_ok=True)
    variables.append(f"checkpoint_every={a.checkpoint_every}")
    ckpt, state_file = os.path.join(tmp, "classic_restart.h5"), os.path.join(tmp, "parts.json")
    state = json.load(open(state_file)) if os.path.exists(state_file) else {"wall": 0.0, "parts": 0}
    if os.path.exists(ckpt):
        # the previous part counts up to its last checkpoint; later work is redone
        if "start" in state and os.path.getmtime(ckpt) > state["start"]:
            state["wall"] += os.path.getmtime(ckpt) - state["start"]
        shutil.copyfile(ckpt, os.path.join(tmp, "restart_in.h5"))
        variables.append("restart=restart_in.h5")
    state["start"] = time.time()
    state["parts"] += 1
    with open(state_file + ".tmp", "w") as fh:
        json.dump(state, fh)
    os.replace(state_file + ".tmp", state_file)
    res = run_deck(deck, variables, cwd=tmp, timeout=a.timeout, binary=a.slender)
    row = parse_result(a, y, mu, seed, dt, res)
    if row.get("wall_s"):
        row["wall_s"] = f"{float(row['wall_s']) + state['wall']:.6g}"
    if row["status"] != "failed" or "timeout" not in row.get("error", ""):
        shutil.rmtree(tmp, ignore_errors=True)  # finished: the checkpoint is no longer needed
    return row


def settle(work):
    for d in sorted(os.listdir(work)) if work and os.path.isdir(work) else []:
        ckpt, state_file = os.path.join(work, d, "classic_restart.h5"), os.path.join(work, d, "parts.json")
        if not (os.path.exists(ckpt) and os.path.exists(state_file)):
            continue
        state = json.load(open(state_file))
        if "start" in state and os.path.getmtime(ckpt) > state["start"]:
            state["wall"] += os.path.getmtime(ckpt) - state["start"]
        state.pop("start", None)
        with open(state_file + ".tmp", "w") as fh:
            json.dump(state, fh)
        os.replace(state_file + ".tmp", state_file)
        print(f"{d}: {state['parts']} part(s), {state['wall']:.0f} s up to its last checkpoint")


def parse_result(a, y, mu, seed, dt, res):
    """The table row of a run (slender.run.RunResult): a timed-out run is failed with
    "timeout" in its error (so a kept run directory continues later)."""
    row = {"f": a.f, "s": a.s, "yield": y, "mu": mu, "seed": seed, "dt": f"{dt:.6g}"}
    last = res.results_text[-1] if res.results_text else {}  # verbatim, as the deck printed it
    error = (res.error or "?")[:200].replace(",", ";")
    if last and res.status != "timeout" and (res.returncode == 0 or last.get("ended") == "instability"):
        for k in ("phi", "jammed", "loops", "winding", "ab_ratio", "contacts", "steps", "wall_s"):
            row[k] = last.get(k, "")
        row["class"] = classify(row)
        # a run the guard stopped is classified from its last good state
        row["status"] = "ok" if res.returncode == 0 else "unstable"
        if res.returncode != 0:
            row["error"] = error
    else:
        row["status"] = "failed"
        row["error"] = error
    return row


def key(r):
    return (round(float(r["yield"]), 6), round(float(r["mu"]), 6), int(r["seed"]))


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


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--slender", default=os.path.join(ROOT, "build", "slender"))
    ap.add_argument("--examples", default=os.path.join(ROOT, "examples"))
    ap.add_argument("--f", type=float, default=50)
    ap.add_argument("--s", type=float, default=0.05, help="feed speed (the thesis' s, reading (a))")
    ap.add_argument("--yields", type=float, nargs="+", default=[round(0.005 * i, 3) for i in range(13)])
    ap.add_argument("--mus", type=float, nargs="+", default=[round(0.05 * i, 2) for i in range(13)])
    ap.add_argument("--seeds", type=int, nargs="+", default=list(range(1, 10)))
    ap.add_argument("--jobs", type=int, default=max(1, (os.cpu_count() or 2)))
    ap.add_argument("--max-steps", type=float, default=1e9)
    ap.add_argument("--timeout", type=float, default=None, help="seconds per run")
    ap.add_argument("--retry-failed", action="store_true")
    ap.add_argument("--work", default=None,
                    help="keep each run's directory here, so an interrupted run continues from its checkpoint")
    ap.add_argument("--checkpoint-every", type=int, default=1000000,
                    help="steps between checkpoints of a run (with --work)")
    ap.add_argument("--no-retry-dt", dest="retry_dt", action="store_false",
                    help="do not repeat a run stopped by the instability guard with dt / 2")
    ap.add_argument("--snapshot", action="store_true",
                    help="copy the binary's decks to a temporary folder first, so edits during a "
                         "long sweep cannot change it")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "crumple2d", "phase_diagram_f50"))
    ap.add_argument("--settle", action="store_true",
                    help="only fold each kept run's time up to its last checkpoint into its wall "
                         "time and exit: before the --work folder moves to another machine (a "
                         "fresh clone gives the checkpoint a new modification time)")
    a = ap.parse_args()
    if a.settle:
        settle(a.work)
        return
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    path = a.out + ".csv"
    rows = load(path)
    if rows and list(rows[0].keys()) != FIELDS:  # a file from an older version: new columns
        with open(path, "w", newline="") as fh:
            w = csv.DictWriter(fh, FIELDS, extrasaction="ignore")
            w.writeheader()
            w.writerows(rows)
    unstable = set()
    if a.retry_failed:
        unstable = {key(r) for r in rows if r["status"] != "ok" and "instability" in (r.get("error") or "")}
        rows = [r for r in rows if r["status"] == "ok"]
        with open(path, "w", newline="") as fh:
            w = csv.DictWriter(fh, FIELDS)
            w.writeheader()
            w.writerows(rows)
    done = {key(r) for r in rows}
    todo = [(y, mu, s) for y in a.yields for mu in a.mus for s in a.seeds
            if (round(y, 6), round(mu, 6), s) not in done]
    print(f"{len(done)} runs done, {len(todo)} to go -> {path}", flush=True)
    if a.snapshot:
        snap = tempfile.mkdtemp(prefix="slender_sweep_")
        shutil.copytree(a.examples, os.path.join(snap, "examples"))
        a.examples = os.path.join(snap, "examples")
    lock = threading.Lock()
    if not os.path.exists(path):
        with open(path, "w", newline="") as fh:
            csv.DictWriter(fh, FIELDS).writeheader()

    def job(t):
        row = run_one(a, *t, unstable_before=(round(t[0], 6), round(t[1], 6), t[2]) in unstable)
        with lock:  # append at once: an interrupted sweep loses at most the runs in flight
            with open(path, "a", newline="") as fh:
                csv.DictWriter(fh, FIELDS).writerow(row)
            print(f"yield {t[0]:g} mu {t[1]:g} seed {t[2]}: {row['status']} {row.get('class', '')} "
                  f"phi {row.get('phi', '')}", flush=True)
        return row

    with cf.ThreadPoolExecutor(a.jobs) as ex:
        list(ex.map(job, todo))
    rows = load(path)
    draw(rows, a.out, sorted(set(a.yields)), sorted(set(a.mus)), a.f)
    ok = sum(r["status"] == "ok" for r in rows)
    unstable = sum(r["status"] == "unstable" for r in rows)
    print(f"{ok} ok, {unstable} unstable (classified from the last good state), "
          f"{len(rows) - ok - unstable} failed; wrote {a.out}.png {a.out}_phi.png")


if __name__ == "__main__":
    main()

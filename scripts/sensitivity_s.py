#!/usr/bin/env python3
"""Sensitivity of the 2D crumpling results to the thesis' undefined parameter s
(docs/models.md §2.6): reading (a) s = injection speed (with K_h = 0.05 K_e), reading (b)
s = hardening ratio K_h/K_e (with a fixed feed speed). Runs a crumpling deck to
jamming for each value under each reading, two runs at a time, and writes a CSV
and a Markdown table of the jamming density, injection force, contacts and the
morphology indicators. A study, not a test.

  /usr/bin/python3 scripts/sensitivity_s.py [--deck classic] [--f 10] [--values 0.04 0.06 0.08]
"""
import argparse
import concurrent.futures as cf
import csv
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))
from slender.run import run_deck  # noqa: E402


def run(binary, examples, deck, f, reading, value, speed_b, seed):
    variables = [f"f={f}", "output=false", f"seed={seed}"]
    if reading == "a":
        variables += [f"s={value}", "hardening=0.05"]
    else:
        variables += [f"s={speed_b}", f"hardening={value}"]
    res = run_deck(os.path.join(examples, "crumple2d", deck + ".lua"), variables, binary=binary)
    row = {}
    for rec in res.results_text:  # verbatim, as the deck printed them
        row.update(rec)
    # the deck reports its feed speed as s; the studied value is s_value
    row.update({"reading": reading, "s_value": value, "seed": seed,
                "status": "ok" if res.returncode == 0 else "failed"})
    if res.returncode != 0:
        row["error"] = (res.error or "?")[:200]
    return row


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--slender", default=os.path.join(ROOT, "build", "slender"))
    ap.add_argument("--examples", default=os.path.join(ROOT, "examples"),
                    help="examples folder (a copy keeps a long study independent of edits)")
    ap.add_argument("--deck", default="classic")
    ap.add_argument("--f", type=float, default=10)
    ap.add_argument("--values", type=float, nargs="+", default=[0.04, 0.06, 0.08])
    ap.add_argument("--speed-b", type=float, default=0.05, help="feed speed under reading (b)")
    ap.add_argument("--seeds", type=int, nargs="+", default=[1])
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "crumple2d"))
    a = ap.parse_args()
    jobs = [(r, v, s) for r in ("a", "b") for v in a.values for s in a.seeds]
    with cf.ThreadPoolExecutor(a.jobs) as ex:
        rows = list(ex.map(lambda j: run(a.slender, a.examples, a.deck, a.f, j[0], j[1], a.speed_b, j[2]), jobs))
    os.makedirs(a.out, exist_ok=True)
    keys = sorted({k for r in rows for k in r})
    stem = os.path.join(a.out, f"s_sensitivity_{a.deck}_f{a.f:g}")
    with open(stem + ".csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)
    with open(stem + ".md", "w") as fh:
        fh.write(f"# Sensitivity to s: {a.deck}, f = {a.f:g}, seeds {a.seeds}\n\n")
        fh.write("(a): s is the feed speed, K_h = 0.05 K_e. "
                 f"(b): s is K_h / K_e, feed speed {a.speed_b}.\n\n")
        fh.write("| reading | s | seed | jamming phi | force | contacts | A/B | winding | steps | wall s | status |\n")
        fh.write("|---|---|---|---|---|---|---|---|---|---|---|\n")
        for r in rows:
            fh.write("| {reading} | {s} | {seed} | {phi} | {force} | {contacts} | {ab} | {w} | {steps} | {wall} | {status} |\n".format(
                reading=r["reading"], s=r["s_value"], seed=r["seed"], phi=r.get("phi", "-")[:6],
                force=r.get("force", "-")[:6], contacts=r.get("contacts", "-"), ab=r.get("ab_ratio", "-")[:5],
                w=r.get("winding", "-")[:5], steps=r.get("steps", "-"), wall=r.get("wall_s", "-")[:5],
                status=r["status"] + (": " + r["error"] if "error" in r else "")))
    print(open(stem + ".md").read())
    print("wrote", stem + ".csv", stem + ".md")


if __name__ == "__main__":
    main()

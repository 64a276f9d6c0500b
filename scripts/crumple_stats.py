#!/usr/bin/env python3
"""Statistics of 2D crumpling runs (docs/models.md §2.7, §2.8; thesis eq. 3.3):

  loops     N_l ~ phi^gamma and contacts N_c ~ phi^mu, log-log fits over the thermo
            CSVs of crumpling runs (columns feed.phi, loops.loops,
            contact/node-edge.contacts)
  force     F ~ (phi_c - phi)^beta from the relaxed force samples of
            examples/crumple2d/force.lua (phi_c and beta fitted together)
  spiral    bending energy E_b(phi) of the spiral scene against the analytic spiral
            model of §2.8, both the thesis' printed form (3.10) and the corrected one,
            the constant C matched at the first sample
  jam       where a run jams under each stop rule of docs/models.md §2.4: the packing
            density at which the averaged injection force (feed.force_avg) first
            exceeds each threshold F_stop, and where it first grows tenfold within
            dphi = 0.005; the e-folding dphi of F near the stop says how much phi_jam
            moves per doubling of F_stop. Give each run's thermo CSV(s) joined by '+'
            (a restarted run appends to a second file); runs made with the threshold
            raised (-v jam_force=1e9) show every threshold.

Each mode prints its fit with standard errors and writes a CSV and a PNG.

  /usr/bin/python3 scripts/crumple_stats.py loops classic_thermo.csv [more.csv ...] --out docs/crumple2d/loops
  /usr/bin/python3 scripts/crumple_stats.py force force_samples.csv --out docs/crumple2d/force
  /usr/bin/python3 scripts/crumple_stats.py spiral spiral_thermo.csv --radius 10 --out docs/crumple2d/spiral
  /usr/bin/python3 scripts/crumple_stats.py jam f15_thermo.csv a.csv+b.csv --labels f=15 f=50 --out docs/crumple2d/jam
"""
import argparse
import csv
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))
# the measures live in the package; the names stay importable from here
from slender.crumple import (first_crossing, first_growth, linfit, power_law, read,  # noqa: E402,F401
                             read_run, spiral_model)


def plot(path, series, xlabel, ylabel, logx=True, logy=True, title=""):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5, 4))
    for s in series:
        ax.plot(s["x"], s["y"], s.get("style", "o"), ms=3, label=s["label"])
    if logx:
        ax.set_xscale("log")
    if logy:
        ax.set_yscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def mode_loops(a):
    rows = read(a.files)
    out = {}
    series = []
    for key, name in (("loops.loops", "N_l (loops), gamma"), ("contact/node-edge.contacts", "N_c (contacts), mu")):
        fit = power_law(rows, "feed.phi", key, a.phi_min, a.phi_max)
        if fit is None:
            print(f"{key}: fewer than 3 samples with a positive count")
            continue
        out[key] = fit
        print(f"{name}: exponent {fit['exponent']:.3f} +- {fit['stderr']:.3f} "
              f"(r^2 {fit['r2']:.3f}, {fit['n']} samples, phi in [{a.phi_min}, {a.phi_max}])")
        xs = np.linspace(fit["x"].min(), fit["x"].max(), 50)
        series += [{"x": fit["x"], "y": fit["y"], "label": key},
                   {"x": xs, "y": fit["prefactor"] * xs ** fit["exponent"], "style": "-",
                    "label": f"phi^{fit['exponent']:.2f}"}]
    with open(a.out + ".csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["quantity", "exponent", "stderr", "prefactor", "r2", "samples", "phi_min", "phi_max", "files"])
        for k, fit in out.items():
            w.writerow([k, f"{fit['exponent']:.4f}", f"{fit['stderr']:.4f}", f"{fit['prefactor']:.4g}",
                        f"{fit['r2']:.4f}", fit["n"], a.phi_min, a.phi_max, " ".join(a.files)])
    if series:
        plot(a.out + ".png", series, "packing density phi", "count", title="loops and contacts vs phi")
    print("wrote", a.out + ".csv", a.out + ".png")


def mode_force(a):
    rows = [r for r in read(a.files) if r.get("force", 0) > 0 and r.get("relaxed", 1) > 0]
    phi = np.array([r["phi"] for r in rows])
    F = np.array([r["force"] for r in rows])
    keep = phi >= a.phi_min
    phi, F = phi[keep], F[keep]
    if len(phi) < 4:
        raise SystemExit("force: fewer than 4 relaxed samples")
    # F = A (phi_c - phi)^beta: for each phi_c above the last sample a linear fit in
    # log-log; phi_c is the one with the smallest residual
    best = None
    for pc in phi.max() + np.geomspace(1e-4, 0.5, 400):
        b, c, sb, r2 = linfit(np.log(pc - phi), np.log(F))
        resid = np.log(F) - (c + b * np.log(pc - phi))
        sse = resid @ resid
        if best is None or sse < best[0]:
            best = (sse, pc, b, c, sb, r2)
    sse, pc, b, c, sb, r2 = best
    print(f"F ~ (phi_c - phi)^beta: phi_c = {pc:.4f}, beta = {b:.3f} +- {sb:.3f} (at fixed phi_c), "
          f"r^2 {r2:.3f}, {len(phi)} relaxed samples with phi >= {a.phi_min}")
    with open(a.out + ".csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["phi_c", "beta", "beta_stderr", "prefactor", "r2", "samples", "files"])
        w.writerow([f"{pc:.5f}", f"{b:.4f}", f"{sb:.4f}", f"{math.exp(c):.4g}", f"{r2:.4f}", len(phi),
                    " ".join(a.files)])
    xs = np.linspace(phi.min(), phi.max(), 100)
    plot(a.out + ".png", [{"x": phi, "y": F, "label": "relaxed injection force"},
                          {"x": xs, "y": math.exp(c) * (pc - xs) ** b, "style": "-",
                           "label": f"(phi_c - phi)^{b:.2f}, phi_c = {pc:.3f}"}],
         "packing density phi", "injection force", logx=False, title="injection force vs phi")
    print("wrote", a.out + ".csv", a.out + ".png")


def mode_spiral(a):
    rows = [r for r in read(a.files) if "energy.bend" in r]
    phi = np.array([r["feed.phi"] for r in rows])
    E = np.array([r["energy.bend"] for r in rows])
    # phi is 0 before the feed's first step; the model starts at the starting density
    keep = (phi > 0) & (phi >= a.phi_min)
    phi, E = phi[keep], E[keep]
    if len(phi) < 3:
        raise SystemExit("spiral: fewer than 3 samples")
    out = []
    series = [{"x": phi, "y": E, "label": "simulation E_b"}]
    hi = phi <= a.report_max
    for printed in (False, True):
        m = spiral_model(phi, a.radius, a.diameter, a.YI, printed)
        name = "printed (3.10)" if printed else "corrected"
        # C as in the thesis (matched at the starting density) and by least squares
        for how, C in (("start", E[0] - m[0]), ("lsq", float(np.mean(E[hi] - m[hi])))):
            model = m + C
            rel = np.abs(E - model) / np.maximum(np.abs(E), 1e-300)
            sel = hi & (E > 0.05 * E.max())   # relative errors of a nearly straight wire mean nothing
            med, mx = float(np.median(rel[sel])), float(rel[sel].max())
            print(f"spiral model {name}, C from {how}: C = {C:.4g}; |E - model| / E for phi in "
                  f"[{phi[sel].min():.3f}, {a.report_max}]: median {med:.3f}, max {mx:.3f}; "
                  f"at the last sample (phi = {phi[-1]:.3f}) {rel[-1]:.3f}")
            out.append((name, how, C, med, mx, rel[-1]))
            series.append({"x": phi, "y": model, "style": "-", "label": f"model {name}, C: {how}"})
    with open(a.out + ".csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["model", "C_from", "C", "median_rel_dev", "max_rel_dev", "last_rel_dev",
                    "phi_report_max", "last_phi", "R", "d", "YI", "files"])
        for name, how, C, med, mx, last in out:
            w.writerow([name, how, f"{C:.5g}", f"{med:.4f}", f"{mx:.4f}", f"{last:.4f}", a.report_max,
                        f"{phi[-1]:.4f}", a.radius, a.diameter, a.YI, " ".join(a.files)])
    plot(a.out + ".png", series, "packing density phi", "bending energy", logx=False, logy=False,
         title=f"spiral phase, R = {a.radius:g} d")
    print("wrote", a.out + ".csv", a.out + ".png")


def mode_jam(a):
    labels = a.labels or a.files
    if len(labels) != len(a.files):
        raise SystemExit("jam: give one label per run")
    series, out = [], []
    for spec, label in zip(a.files, labels):
        # --phi-min skips the buckling of the initial straight wire, whose force
        # peak is not a jam
        rows = [r for r in read_run(spec) if "feed.force_avg" in r and r["feed.phi"] >= a.phi_min]
        phi = np.array([r["feed.phi"] for r in rows])
        F = np.array([r["feed.force_avg"] for r in rows])
        # e-folding of F in phi over the last decade of force below the top threshold
        top = max(t for t in a.thresholds if np.any(F > t)) if np.any(F > min(a.thresholds)) else F.max()
        stop = np.argmax(F > top) if np.any(F > top) else len(F)
        sel = (F[:stop] > top / 10) & (F[:stop] > 0)
        efold = float("nan")
        if sel.sum() >= 5:
            b, _, sb, _ = linfit(phi[:stop][sel], np.log(F[:stop][sel]))
            efold = 1 / b if b > 0 else float("nan")
        grow = first_growth(phi, F, 10.0, 0.005)
        print(f"{label}: {len(F)} samples up to phi = {phi.max():.4f}, F_max {F.max():.1f}; "
              f"e-folding dphi of F below {top:g}: {efold:.4f} (phi_jam moves {efold * math.log(2):.4f} "
              f"per doubling of F_stop); tenfold growth within 0.005 first at phi = {grow:.4f}")
        for t in a.thresholds:
            pj = first_crossing(phi, F, t)
            print(f"  F_stop = {t:g}: phi_jam = {pj:.4f}")
            out.append([label, t, f"{pj:.5f}", f"{efold:.5f}", f"{grow:.5f}", f"{phi.max():.5f}",
                        f"{F.max():.4g}"])
        series.append({"x": phi, "y": np.maximum(F, 1e-3), "style": "-", "label": label})
    with open(a.out + ".csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["run", "F_stop", "phi_jam", "efold_dphi", "phi_growth10", "phi_last", "F_max"])
        w.writerows(out)
    for t in a.thresholds:
        series.append({"x": [0, max(s["x"].max() for s in series[:len(labels)])], "y": [t, t],
                       "style": ":", "label": f"F_stop = {t:g}"})
    plot(a.out + ".png", series, "packing density phi", "injection force (1e3-step average)",
         logx=False, title="injection force until the wire jams")
    print("wrote", a.out + ".csv", a.out + ".png")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("mode", choices=["loops", "force", "spiral", "jam"])
    ap.add_argument("files", nargs="+")
    ap.add_argument("--out", required=True, help="output stem (CSV and PNG)")
    ap.add_argument("--phi-min", type=float, default=0.0)
    ap.add_argument("--phi-max", type=float, default=1.0)
    ap.add_argument("--radius", type=float, default=100.0, help="cavity radius R (spiral)")
    ap.add_argument("--diameter", type=float, default=1.0)
    ap.add_argument("--YI", type=float, default=60.0, help="bending stiffness YI = k2 l0 (spiral)")
    ap.add_argument("--report-max", type=float, default=0.9, help="spiral: deviations reported up to this phi")
    ap.add_argument("--labels", nargs="*", help="jam: one label per run")
    ap.add_argument("--thresholds", nargs="*", type=float, default=[25, 50, 100, 200, 400],
                    help="jam: stop thresholds F_stop")
    a = ap.parse_args()
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    {"loops": mode_loops, "force": mode_force, "spiral": mode_spiral, "jam": mode_jam}[a.mode](a)


if __name__ == "__main__":
    main()

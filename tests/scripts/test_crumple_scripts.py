#!/usr/bin/env python3
"""Checks the fits of scripts/crumple_stats.py on synthetic data with known answers,
and the morphology classes of scripts/phase_diagram.py."""
import csv
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import crumple_stats  # noqa: E402
import phase_diagram  # noqa: E402


def write(path, header, rows):
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(header)
        w.writerows(rows)


def stats(*args):
    out = subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "crumple_stats.py"), *args],
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    return out.stdout


def read_csv(path):
    with open(path) as fh:
        return list(csv.DictReader(fh))


def main():
    rng = np.random.default_rng(3)
    with tempfile.TemporaryDirectory() as tmp:
        # N_l = 4 phi^1.5 and N_c = 300 phi^2.8 with 2 % noise
        phi = np.linspace(0.1, 0.6, 40)
        noise = lambda: np.exp(0.02 * rng.standard_normal(phi.size))
        write(os.path.join(tmp, "t.csv"), ["feed.phi", "loops.loops", "contact/node-edge.contacts"],
              zip(phi, 4 * phi ** 1.5 * noise(), 300 * phi ** 2.8 * noise()))
        stats("loops", os.path.join(tmp, "t.csv"), "--out", os.path.join(tmp, "loops"))
        fits = {r["quantity"]: float(r["exponent"]) for r in read_csv(os.path.join(tmp, "loops.csv"))}
        assert abs(fits["loops.loops"] - 1.5) < 0.05, fits
        assert abs(fits["contact/node-edge.contacts"] - 2.8) < 0.05, fits

        # F = 5 (0.62 - phi)^-1.2, one sample not at rest (left out of the fit)
        phi = np.linspace(0.1, 0.6, 30)
        F = 5 * (0.62 - phi) ** -1.2 * np.exp(0.01 * rng.standard_normal(phi.size))
        rows = [(p, f, 1) for p, f in zip(phi, F)] + [(0.3, 1e4, 0)]
        write(os.path.join(tmp, "f.csv"), ["phi", "force", "relaxed"], rows)
        stats("force", os.path.join(tmp, "f.csv"), "--out", os.path.join(tmp, "force"))
        r = read_csv(os.path.join(tmp, "force.csv"))[0]
        assert abs(float(r["phi_c"]) - 0.62) < 0.01, r
        assert abs(float(r["beta"]) + 1.2) < 0.1, r

        # a spiral whose energy is the corrected model plus a constant: no deviation
        # from the corrected model, a clear one from the printed form
        phi = np.linspace(0.05, 0.8, 30)
        E = crumple_stats.spiral_model(phi, 50.0, 1.0, 60.0, printed=False) + 123.0
        write(os.path.join(tmp, "s.csv"), ["feed.phi", "energy.bend"], zip(phi, E))
        stats("spiral", os.path.join(tmp, "s.csv"), "--radius", "50", "--out", os.path.join(tmp, "spiral"))
        dev = {(r["model"], r["C_from"]): float(r["max_rel_dev"])
               for r in read_csv(os.path.join(tmp, "spiral.csv"))}
        assert dev[("corrected", "start")] < 1e-6 and dev[("corrected", "lsq")] < 1e-6, dev
        assert dev[("printed (3.10)", "start")] > 0.01, dev

    # morphology classes
    c = phase_diagram.classify
    assert c({"winding": 2.5, "loops": 1, "ab_ratio": 3.0}) == "spiral"
    assert c({"winding": 2.5, "loops": 5, "ab_ratio": 0.3}) == "classic"
    assert c({"winding": 0.3, "loops": 0, "ab_ratio": 0.3}) == "classic"
    assert c({"winding": 0.3, "loops": 4, "ab_ratio": 0.9}) == "plastic"
    # the spiral model's core radius: R_c(0) ~ R, R_c(1) = d (docs/models.md §2.8)
    rc = lambda p: 0.5 * (1 + np.sqrt(1 + 4 * 50.0 ** 2 * (1 - p)))
    assert abs(rc(1.0) - 1.0) < 1e-12 and abs(rc(0.0) - 50.0) < 1
    sweep_resumes_interrupted_runs()
    causes_table_means_and_errors()
    print("crumple scripts: ok")


FAKE_SLENDER = """#!{python}
# stands in for slender: a first part writes a checkpoint and hangs (killed by the
# sweep's timeout); a part given -v restart=... finishes 100 steps after it
import os, sys, time
restart = [v.split("=", 1)[1] for v in sys.argv if v.startswith("restart=")]
step = int(open(restart[0]).read()) if restart else 0
if not restart:
    open("classic_restart.h5", "w").write(str(step + 700))
    time.sleep(30)
print(f"RESULT phi=0.3 jammed=1 loops=4 winding=0.2 ab_ratio=0.3 contacts=9 "
      f"steps={{step + 100}} wall_s=1.5 ended=jam")
"""


def causes_table_means_and_errors():
    """scripts/causes_table.py: the mean over seeds and its standard error, per value; a failed
    run is counted, not averaged."""
    import causes_table
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "study.csv")
        keys = ["value", "seed", "status"] + [k for k, _, _ in causes_table.COLUMNS]
        base = {k: 1.0 for k, _, _ in causes_table.COLUMNS}
        write(path, keys, [["0.1", 1, "ok"] + [base[k] if k != "phi" else 0.3 for k, _, _ in causes_table.COLUMNS],
                           ["0.1", 2, "ok"] + [base[k] if k != "phi" else 0.5 for k, _, _ in causes_table.COLUMNS],
                           ["0.1", 3, "failed"] + ["" for _ in causes_table.COLUMNS],
                           ["1", 1, "ok"] + [2.0 for _ in causes_table.COLUMNS]])
        rows = causes_table.rows_of("drag", path)
    assert len(rows) == 2, rows
    # mean 0.4, standard error sqrt(0.02 / 2) = 0.1; the failed seed is named
    assert rows[0].startswith("| drag = 0.1 | 2 (1 failed) | 0.400 ± 0.100 |"), rows[0]
    assert rows[1].startswith("| drag = 1 | 1 | 2.000 |"), rows[1]


def sweep_resumes_interrupted_runs():
    """An interrupted run of the phase-diagram sweep continues from its checkpoint:
    the restarted part is given the checkpoint, its steps continue, its wall time adds
    the first part's time up to the checkpoint, and the run directory goes at the end."""
    with tempfile.TemporaryDirectory() as tmp:
        fake = os.path.join(tmp, "slender")
        with open(fake, "w") as fh:
            fh.write(FAKE_SLENDER.format(python=sys.executable))
        os.chmod(fake, 0o755)
        common = [sys.executable, os.path.join(ROOT, "scripts", "phase_diagram.py"), "--slender", fake,
                  "--f", "8", "--yields", "0.02", "--mus", "0.2", "--seeds", "1", "--jobs", "1",
                  "--work", os.path.join(tmp, "work"), "--no-retry-dt", "--out", os.path.join(tmp, "pd")]
        out = subprocess.run(common + ["--timeout", "1"], capture_output=True, text=True)
        assert out.returncode == 0, out.stderr
        first = read_csv(os.path.join(tmp, "pd.csv"))
        assert first[0]["status"] == "failed" and "timeout" in first[0]["error"], first
        assert len(os.listdir(os.path.join(tmp, "work"))) == 1  # kept for the next part
        # --settle before the folder moves to another machine: the first part's time up
        # to its checkpoint is kept, and the checkpoint's new modification time after a
        # fresh clone (here: a day later) adds nothing
        run_dir = os.path.join(tmp, "work", os.listdir(os.path.join(tmp, "work"))[0])
        out = subprocess.run(common + ["--settle"], capture_output=True, text=True)
        assert out.returncode == 0 and "1 part(s)" in out.stdout, (out.stdout, out.stderr)
        with open(os.path.join(run_dir, "parts.json")) as fh:
            state = json.load(fh)
        assert "start" not in state and 0.0 < state["wall"] < 1.0, state
        later = os.path.getmtime(os.path.join(run_dir, "classic_restart.h5")) + 86400
        os.utime(os.path.join(run_dir, "classic_restart.h5"), (later, later))
        out = subprocess.run(common + ["--retry-failed"], capture_output=True, text=True)
        assert out.returncode == 0, out.stderr
        rows = read_csv(os.path.join(tmp, "pd.csv"))
        assert len(rows) == 1 and rows[0]["status"] == "ok", rows
        assert rows[0]["steps"] == "800", rows  # continued from the checkpoint at 700
        assert 1.5 < float(rows[0]["wall_s"]) < 2.5, rows  # + the first part up to its checkpoint
        assert os.listdir(os.path.join(tmp, "work")) == []


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""scripts/dt_ladder.py on the real engine: a rung of the classic deck (fast mode) at the
old Gear step against adaptive Verlet, one seed each. The rows must be read from the
RESULT lines (a run that failed, or a deck that ignored `-v integrator=`, would show), the
summary must name both rungs, and a second call (the script drives workflows/dt_ladder.smk)
must keep the finished runs instead of redoing them."""
import csv
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def main():
    slender = sys.argv[1]
    script = os.path.join(ROOT, "scripts", "dt_ladder.py")
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "ladder")
        args = [sys.executable, script, "--slender", slender, "--deck", "crumple2d/classic",
                "--var", "fast=1", "--var", "max_phi=0.15", "--rung", "gear:0.00316227766",
                "--rung", "verlet:auto", "--seeds", "1", "--cores", "1",
                "--results", os.path.join(tmp, "results"), "--out", out]
        p = subprocess.run(args, capture_output=True, text=True)
        assert p.returncode == 0, p.stdout + p.stderr
        with open(out + ".csv") as fh:
            rows = {r["rung"]: r for r in csv.DictReader(fh)}
        assert set(rows) == {"gear:0.00316227766", "verlet:auto"}, rows
        for r in rows.values():
            assert r["status"] == "ok" and float(r["phi"]) >= 0.15, r
        # Verlet at its auto step takes far fewer steps than Gear at the given one
        assert float(rows["verlet:auto"]["steps"]) < 0.5 * float(rows["gear:0.00316227766"]["steps"]), rows
        with open(out + ".md") as fh:
            md = fh.read()
        assert "| gear:0.00316227766 | 1 (0)" in md and "| verlet:auto | 1 (0)" in md, md
        # the same ladder again: nothing is run again (a missing engine would fail every run)
        p = subprocess.run(args[:2] + ["--slender", "/bin/false"] + args[4:], capture_output=True, text=True)
        assert p.returncode == 0 and "rule point:" not in p.stdout + p.stderr, p.stdout + p.stderr
        with open(out + ".csv") as fh:
            assert {r["rung"]: r for r in csv.DictReader(fh)} == rows
    print("dt_ladder: ok")


if __name__ == "__main__":
    main()

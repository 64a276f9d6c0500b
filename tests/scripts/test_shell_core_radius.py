#!/usr/bin/env python3
"""scripts/shell_core_radius.py on the real engine, through its workflow: two thicknesses
on a coarse disc up to phi_e = 1 give one row each, with both core radii (energy and
stretching criteria) inside the disc; a second call runs nothing and gives the same
table."""
import csv
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def main():
    slender = sys.argv[1]
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "core")
        cmd = [sys.executable, os.path.join(ROOT, "scripts", "shell_core_radius.py"), "--slender", slender,
               "--h", "0.04", "0.02", "--levels", "1", "--edge", "0.25", "--phi", "1", "--results",
               os.path.join(tmp, "res"), "--out", out, "--cores", "2"]
        p = subprocess.run(cmd, capture_output=True, text=True)
        assert p.returncode == 0, p.stdout + p.stderr
        with open(out + ".csv") as fh:
            rows = list(csv.DictReader(fh))
        assert os.path.getsize(out + ".png") > 0
        assert sorted(float(r["h"]) for r in rows) == [0.02, 0.04], rows
        for r in rows:
            assert r["status"] == "ok" and 0 < float(r["R_C"]) < 1, r
            assert 0 < float(r["R_C_s"]) < 1 and int(r["fire_steps"]) > 0, r
        again = subprocess.run(cmd, capture_output=True, text=True)
        assert again.returncode == 0 and "Nothing to be done" in again.stdout + again.stderr, again.stderr[-2000:]
        with open(out + ".csv") as fh:
            assert list(csv.DictReader(fh)) == rows
    print("shell_core_radius: ok")


if __name__ == "__main__":
    main()

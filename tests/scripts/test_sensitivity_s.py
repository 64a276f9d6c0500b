#!/usr/bin/env python3
"""scripts/sensitivity_s.py on the real engine, through its workflow: under reading (a) the
studied value is the feed speed the deck runs at, under (b) the feed speed stays --speed-b
(the value goes to the hardening slope); each run ends jammed; a second call runs nothing."""
import csv
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def main():
    slender = sys.argv[1]
    with tempfile.TemporaryDirectory() as tmp:
        cmd = [sys.executable, os.path.join(ROOT, "scripts", "sensitivity_s.py"), "--slender", slender,
               "--f", "8", "--values", "0.04", "0.06", "--speed-b", "0.03", "--results",
               os.path.join(tmp, "res"), "--out", os.path.join(tmp, "out"), "--cores", "2"]
        p = subprocess.run(cmd, capture_output=True, text=True)
        assert p.returncode == 0, p.stdout + p.stderr
        with open(os.path.join(tmp, "out", "s_sensitivity_classic_f8.csv")) as fh:
            rows = list(csv.DictReader(fh))
        assert os.path.getsize(os.path.join(tmp, "out", "s_sensitivity_classic_f8.md")) > 0
        assert sorted((r["reading"], float(r["s_value"])) for r in rows) == [
            ("a", 0.04), ("a", 0.06), ("b", 0.04), ("b", 0.06)], rows
        for r in rows:
            assert r["status"] == "ok" and float(r["jammed"]) == 1, r
            speed = float(r["s_value"]) if r["reading"] == "a" else 0.03
            assert abs(float(r["s"]) - speed) < 1e-12, r
        # (b) at one speed with two hardening slopes: different runs, not one run twice
        b = [r for r in rows if r["reading"] == "b"]
        assert b[0]["steps"] != b[1]["steps"] or b[0]["phi"] != b[1]["phi"], b
        again = subprocess.run(cmd, capture_output=True, text=True)
        assert again.returncode == 0 and "Nothing to be done" in again.stdout + again.stderr, again.stderr[-2000:]
    print("sensitivity_s: ok")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""scripts/first_buckle.py on the real engine: in a small cavity (f = 12) a slow feed is
quasi-static and the span buckles as one arch, as docs/models.md §7.2 expects. At f = 100
the drag the classic deck used until 2026-12-07 (drag_factor = 1) resists the fed wire, and
it buckles next to the channels; under the deck's converged drag (a thousandth of that,
docs/crumple2d/causes.md) the middle of the span buckles first."""
import csv
import os
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import first_buckle  # noqa: E402


def main():
    slender = sys.argv[1]
    # the measurement on hand-made shapes: one arch in the middle, two buckles at the ends
    x = np.linspace(-20, 20, 401)
    peak, amp, hw, central = first_buckle.measure(x, 6 * np.cos(np.pi * x / 40), 20)
    assert peak < 0.01 and abs(amp - 6) < 1e-9 and hw == 1 and central == 1.0, (peak, amp, hw, central)
    peak, amp, hw, central = first_buckle.measure(x, 5 * np.sin(np.pi * x / 10) * (np.abs(x) > 10), 20)
    # one down at the left, one up at the right, the middle straight
    assert peak > 0.5 and hw == 2 and central == 0.0, (peak, hw, central)
    assert abs(first_buckle.span_number(100, 0.08) - 0.2092) < 1e-4

    with tempfile.TemporaryDirectory() as tmp:
        def study(f, v, feed, *deck_vars):
            name = f"{f}" + "".join(x.replace("=", "") for x in deck_vars)
            out = os.path.join(tmp, f"fb{name}")
            p = subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "first_buckle.py"), "--slender",
                                slender, "--f", str(f), "--speeds", str(v), "--feed", str(feed), "--out", out,
                                "--results", os.path.join(tmp, f"res{name}"), "--cores", "2",
                                *(["--set", *deck_vars] if deck_vars else [])],
                               capture_output=True, text=True)
            assert p.returncode == 0, p.stdout + p.stderr
            with open(out + ".csv") as fh:
                rows = list(csv.DictReader(fh))
            assert len(rows) == 1 and rows[0]["status"] == "ok", rows
            assert os.path.getsize(out + ".png") > 0
            return {k: float(v) for k, v in rows[0].items() if k not in ("status", "error")}

        # Pi = 0.006: quasi-static, so the span buckles as one arch
        r = study(12, 0.02, 0.25)
        assert r["half_waves"] == 1 and r["central"] > 0.9 and r["amplitude"] > 2.0, r
        # Pi = 0.21 (the classic deck at f = 100) under the old drag: the wire buckles next to
        # the channels before the span can follow, and the middle stays nearly straight
        r = study(100, 0.08, 0.2, "drag_factor=1")
        assert r["half_waves"] >= 2 and r["central"] < 0.5 and r["peak_x_over_r"] > 0.5, r
        # the deck's default drag: the largest deflection lies in the middle half of the span
        r = study(100, 0.08, 0.2)
        assert r["central"] > 0.9 and r["peak_x_over_r"] < 0.5, r
    print("first_buckle: ok")


if __name__ == "__main__":
    main()

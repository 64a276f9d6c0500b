#!/usr/bin/env python3
"""scripts/hardening_study.py on the real engine: the hardening slope K_h of the bending
law decides the classic deck's morphology under the drag the deck used until 2026-12-07
(drag_factor = 1, docs/crumple2d/causes.md). With the default K_h = 0.05 K_e the wire folds
at plastic hinges along the feed axis and never reaches the wall; with K_h = 0.8 K_e it
makes large loops that fill the outer ring and touch the wall (the thesis' classic
picture). If the hysteresis law ignored K_h, both runs would look alike."""
import csv
import os
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import hardening_study  # noqa: E402


def main():
    slender = sys.argv[1]
    # the measures on hand-made wires in a cavity of radius 10: a ring at 0.8 r lies wholly
    # in the outer ring, a straight wire along the axis has a half width of 0
    t = np.linspace(0, 2 * np.pi, 400, endpoint=False)
    outer, half = hardening_study.shape_measures(np.c_[8 * np.cos(t), 8 * np.sin(t)], 10)
    assert outer == 1.0 and abs(half - 0.8 * np.percentile(np.abs(np.sin(t)), 90)) < 1e-12, (outer, half)
    x = np.linspace(-12, 12, 241)
    outer, half = hardening_study.shape_measures(np.c_[x, 0 * x], 10)
    # nodes in the channels (|x| >= r - 0.5) do not count
    assert abs(outer - np.mean(np.abs(x[np.abs(x) < 9.5]) > 7)) < 1e-12 and half == 0.0, (outer, half)

    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "hs")
        p = subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "hardening_study.py"), "--slender",
                            slender, "--f", "12", "--ratios", "0.05", "0.8", "--seeds", "1", "--max-phi", "0.3",
                            "--set", "drag_factor=1",
                            "--out", out, "--results", os.path.join(tmp, "results"), "--cores", "2"],
                           capture_output=True, text=True)
        assert p.returncode == 0, p.stdout + p.stderr
        with open(out + ".csv") as fh:
            rows = {float(r["value"]): r for r in csv.DictReader(fh)}
        for ext in (".md", ".png"):
            assert os.path.getsize(out + ext) > 0
    soft, hard = rows[0.05], rows[0.8]
    assert soft["status"] == "ok" and hard["status"] == "ok", rows
    # K_h = 0.05 K_e: folds along the axis, plastic by the A/B criterion, no wall contact
    assert float(soft["ab_ratio"]) > 1.0 and float(soft["wall_contacts"]) == 0, soft
    # K_h = 0.8 K_e: classic by the A/B criterion, loops along the wall
    assert float(hard["ab_ratio"]) < 0.5 and float(hard["wall_contacts"]) > 0, hard
    assert float(hard["outer_share"]) > float(soft["outer_share"]) + 0.15, (soft, hard)
    print("hardening_study: ok")


if __name__ == "__main__":
    main()

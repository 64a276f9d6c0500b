#!/usr/bin/env python3
"""Runs scripts/shell_plots.py on a small synthetic surface file and CSVs (the layout
dump "shell" and the shell example decks write) and checks that the PNGs appear."""
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCRIPT = os.path.join(ROOT, "scripts", "shell_plots.py")


def run(*args):
    subprocess.run([sys.executable, SCRIPT, *args], check=True, capture_output=True)


def main():
    with tempfile.TemporaryDirectory() as d:
        h5 = os.path.join(d, "surface.h5")
        with h5py.File(h5, "w") as f:
            f["mesh/triangles"] = np.array([[0, 1, 2], [0, 2, 3]], dtype=float)
            pos = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0.2], [0, 1, 0]], dtype=float)
            f["frames/position/value"] = pos[None]
            f["frames/koiter.Ub/value"] = np.array([[[0.1], [2.0]]])
        run("render", h5, os.path.join(d, "s.png"))
        e = os.path.join(d, "econe.csv")
        with open(e, "w") as f:
            f.write("phi_e,E_s,E_b,Eb_hat,area,wings,a2,a3,contacts,gamma,steps,wall_s\n")
            for k, phi in enumerate([1, 2, 3, 4]):
                f.write(f"{phi},0.1,0.2,{phi},3.2,2,0.1,0,{0 if k < 2 else 5},{-1 if k < 3 else 1.2},10,1\n")
        run("econe", e, os.path.join(d, "e.png"))
        s = os.path.join(d, "sphere.csv")
        with open(s, "w") as f:
            f.write("time,f,E_s,E_b,Eb_hat,self_contacts,wall_contacts,wall_force,dt,rejected,wall_s\n")
            for t in range(3):
                f.write(f"{t},{2 + t * 0.1},{0.1 * t},{0.2 * t},1,0,3,1,1e-4,0,1\n")
        run("sphere", s, s, os.path.join(d, "p.png"))
        run("sphere", s, os.path.join(d, "p1.png"))
        b = os.path.join(d, "branches.csv")
        with open(b, "w") as f:
            f.write("branch,phi_e,E_s,E_b,Eb_hat,area,wings,a2,a3,contacts,far_contacts,gamma,steps,wall_s\n")
            for br, phi, g in (("symmetric", 5, 1.5), ("symmetric", 6, 1.5), ("released", 6, 0.3),
                               ("skewed", 5.5, 0.4), ("release_test", 5.5, -1)):
                f.write(f"{br},{phi},1,2,{phi},3.1,2,0,0,4,4,{g},10,1\n")
        run("branches", b, os.path.join(d, "b.png"))
        for png in ("s.png", "e.png", "p.png", "p1.png", "b.png"):
            assert os.path.getsize(os.path.join(d, png)) > 1000, png
    print("shell scripts: ok")


if __name__ == "__main__":
    main()

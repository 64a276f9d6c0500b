#!/usr/bin/env python3
"""Checks the fits of scripts/crumple_stats.py on synthetic data with known answers,
and the morphology classes of scripts/phase_diagram.py."""
import csv
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
    causes_table_means_and_errors()
    wire_gallery_draws_each_wire()
    print("crumple scripts: ok")


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


def wire_gallery_draws_each_wire():
    """scripts/wire_gallery.py: a panel per wire, ink where the wire lies and none in an empty
    cavity; a run without its record is refused by name."""
    import json

    import matplotlib.image
    with tempfile.TemporaryDirectory() as tmp:
        t = np.linspace(0, 2 * np.pi, 400)
        runs = []
        for name, xy in (("ring", np.c_[5 * np.cos(t), 5 * np.sin(t)]), ("line", np.c_[np.linspace(-9, 9, 50), 0 * t[:50]])):
            np.save(os.path.join(tmp, name + ".npy"), xy)
            with open(os.path.join(tmp, name + ".json"), "w") as fh:
                json.dump({"result": {"f": 10, "phi": 0.1, "ab_ratio": 1.0, "loops": 0, "wall_contacts": 0}}, fh)
            runs.append(f"{name}, f = 10={os.path.join(tmp, name + '.npy')}")
        out = os.path.join(tmp, "g.png")
        r = subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "wire_gallery.py"), out, *runs],
                           capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        dark = matplotlib.image.imread(out)[..., :3].mean(axis=2) < 0.3  # the wire, not the grey wall
        w = dark.shape[1]
        left, right = dark[:, : w // 2], dark[:, w // 2:]
        # the line is one long dark row across its panel; the ring crosses its panel's middle
        # column twice and makes no long row
        assert right.mean(axis=1).max() > 0.7, "no line drawn"
        assert left.mean(axis=1).max() < 0.45, "a long dark row in the ring's panel"
        column = left[left.shape[0] // 8:, w // 4].astype(int)  # below the titles
        assert np.count_nonzero(np.diff(column) == 1) == 2, "the ring is not crossed twice"
        os.remove(os.path.join(tmp, "line.json"))
        r = subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "wire_gallery.py"), out, runs[1]],
                           capture_output=True, text=True)
        assert r.returncode != 0 and "line.json" in r.stderr, r.stderr


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""read_checkpoint against damaged, foreign and hand-edited files: each must stop the deck
with exit code 1 and one error line that names the file and what is wrong -- never a crash
(a signal), a hang, or a run that goes on with arrays it cannot index. The untouched file
must still restart (the control), so the test would notice a reader that refuses
everything."""
import os
import shutil
import subprocess
import sys
import tempfile

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
DECK = os.path.join(HERE, "scene.lua")


def run(slender, tmp, mode, path):
    return subprocess.run([slender, DECK, "-v", "mode=" + mode, "-v", "file=" + path],
                          cwd=tmp, capture_output=True, text=True, timeout=120)


def replace(f, name, data):
    del f[name]
    f[name] = data


def main():
    slender = sys.argv[1]
    with tempfile.TemporaryDirectory() as tmp:
        good = os.path.join(tmp, "good.h5")
        p = run(slender, tmp, "write", good)
        assert p.returncode == 0, p.stdout + p.stderr
        with h5py.File(good, "r") as f:
            assert f["styles/contact|node-edge/history"].shape[0] >= 7, "no contact history"
            n = f["nodes/mass"].shape[0]

        def edit(fn):
            def apply(path):
                with h5py.File(path, "r+") as f:
                    fn(f)
            return apply

        def history(value, column):
            def fn(f):
                h = f["styles/contact|node-edge/history"][:]
                h[column] = value
                replace(f, "styles/contact|node-edge/history", h)
            return edit(fn)

        def truncate(path):
            size = os.path.getsize(path)
            with open(path, "r+b") as fh:
                fh.truncate(size // 2)

        def foreign(path):
            os.remove(path)
            with h5py.File(path, "w") as f:
                f["particles/all/position/value"] = np.zeros((3, 4, 3))

        cases = {
            # name: (corruption, words the error line must hold)
            "truncated": (truncate, "not an HDF5 file"),
            "foreign": (foreign, "not a slender checkpoint"),
            "missing": (lambda path: os.remove(path), "no such file"),
            "zero mass": (edit(lambda f: replace(f, "nodes/mass", np.where(
                np.arange(n) == 3, 0.0, f["nodes/mass"][:]))), "node 4 has mass 0"),
            "nan position": (edit(lambda f: replace(f, "nodes/position", np.where(
                np.arange(3 * n).reshape(n, 3) == 7, np.nan, f["nodes/position"][:]))),
                "nodes/position holds NaN"),
            "short velocity": (edit(lambda f: replace(f, "nodes/velocity",
                                                      f["nodes/velocity"][:-2])),
                               "nodes/velocity has"),
            "chain index": (edit(lambda f: replace(f, "chains/w/nodes", np.where(
                np.arange(n) == 5, 1e6, f["chains/w/nodes"][:]))), "is not one of the"),
            "chain twice": (edit(lambda f: replace(f, "chains/w/nodes", np.where(
                np.arange(n) == 5, f["chains/w/nodes"][6], f["chains/w/nodes"][:]))),
                "belongs to two chains"),
            "short rest": (edit(lambda f: replace(f, "chains/w/rest_length",
                                                  f["chains/w/rest_length"][:-3])),
                           "rest lengths"),
            "short property": (edit(lambda f: replace(f, "properties/bend.plastic_curvature",
                                                      f["properties/bend.plastic_curvature"][:-1])),
                               "bend.plastic_curvature' has"),
            "history node 1e6": (history(1e6, 0), "contact/node-edge"),
            "history edge -7": (history(-7, 1), "is not a node and an edge"),
            "history nan": (history(np.nan, 2), "holds NaN"),
            "driven index": (edit(lambda f: replace(f, "styles/feed/driven", np.where(
                np.arange(f["styles/feed/driven"].shape[0]) == 0, 1e6,
                f["styles/feed/driven"][:]))), "driven node index"),
            "short feed scalars": (edit(lambda f: replace(f, "styles/feed/scalars",
                                                          f["styles/feed/scalars"][:2])),
                                   "scalars hold 2 values"),
            "missing style data": (edit(lambda f: f.__delitem__("styles/feed/driven")),
                                   "lacks the array 'driven'"),
            "empty energy": (edit(lambda f: replace(f, "state/energy/bend", np.zeros(0))),
                             "state/energy/bend"),
            # the stream is stored as one number per character
            "bad rng": (edit(lambda f: replace(f, "state/rng", np.array(
                [float(c) for c in b"not a random stream"]))), "state/rng is not"),
            "negative step": (edit(lambda f: replace(f, "state/scalars", np.where(
                np.arange(f["state/scalars"].shape[0]) == 0, -5.0, f["state/scalars"][:]))),
                              "impossible step"),
            "negative shift": (edit(lambda f: replace(f, "state/scalars", np.where(
                np.arange(f["state/scalars"].shape[0]) == 7, -1.0, f["state/scalars"][:]))),
                               "negative Levenberg shift"),
        }
        failures = []
        for name, (corrupt, words) in cases.items():
            path = os.path.join(tmp, name.replace(" ", "_") + ".h5")
            shutil.copy(good, path)
            corrupt(path)
            p = run(slender, tmp, "read", path)
            err = p.stderr.strip().splitlines()
            line = err[-1] if err else ""
            ok = (p.returncode == 1 and "checkpoint '" + path in line or
                  p.returncode == 1 and path in line) and words in line and len(err) == 1
            if not ok:
                failures.append(f"{name}: exit {p.returncode}, stderr {p.stderr.strip()[:400]!r}")
            else:
                print(f"  {name}: {line}")
        # the control: the untouched file restarts and runs on
        p = run(slender, tmp, "read", good)
        if p.returncode != 0:
            failures.append("control: the good checkpoint was refused: " + p.stderr)
        if failures:
            print("\n".join(failures))
            sys.exit(1)
    print(f"checkpoint corruption: ok ({len(cases)} damaged files refused)")


if __name__ == "__main__":
    main()

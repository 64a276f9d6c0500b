#!/usr/bin/env python3
"""SIGTERM and SIGINT stop a run cleanly: the step finishes, outputs are flushed, the last
state is written, the exit code is 130 and one line says where the state is. Continuing
from that state gives the same trajectory bit for bit as a run that was never stopped (the
final positions are compared exactly), for stops at several moments."""
import os
import signal
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
DECK = os.path.join(HERE, "scene.lua")
TOTAL = 3000000  # steps of the reference run (slow feed: the run never ends by itself)


def deck(slender, *variables):
    args = [slender, DECK, "-v", "speed=0.002"]
    for v in variables:
        args += ["-v", v]
    return args


def main():
    slender = sys.argv[1]
    with tempfile.TemporaryDirectory() as tmp:
        ref = os.path.join(tmp, "reference.h5")
        p = subprocess.run(deck(slender, f"steps={TOTAL}", "file=" + ref), cwd=tmp,
                           capture_output=True, text=True, timeout=300)
        assert p.returncode == 0, p.stderr
        with h5py.File(ref, "r") as f:
            x_ref = f["nodes/position"][:]
        stopped = 0
        for k, (sig, wait) in enumerate([(signal.SIGTERM, 0.4), (signal.SIGINT, 1.1),
                                         (signal.SIGTERM, 1.8)]):
            work = os.path.join(tmp, f"stop{k}")
            os.mkdir(work)
            proc = subprocess.Popen(deck(slender, f"steps={TOTAL}", "file=never.h5"), cwd=work,
                                    stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
            time.sleep(wait)
            proc.send_signal(sig)
            out, err = proc.communicate(timeout=60)
            name = signal.Signals(sig).name
            if proc.returncode == 0:
                print(f"  {name} after {wait} s: the run had ended already; skipped")
                continue
            assert proc.returncode == 130, (proc.returncode, err)
            lines = err.strip().splitlines()
            assert len(lines) == 1 and f"interrupted by {name}" in lines[0] and \
                "slender_interrupted.h5" in lines[0], err
            state = os.path.join(work, "slender_interrupted.h5")
            with h5py.File(state, "r") as f:
                done = int(f["state/scalars"][0])
                assert np.isfinite(f["nodes/position"][:]).all()
            assert 0 < done < TOTAL, done
            end = os.path.join(work, "end.h5")
            p = subprocess.run(deck(slender, "mode=read", "file=" + state,
                                    f"steps={TOTAL - done}", "out=" + end),
                               cwd=work, capture_output=True, text=True, timeout=300)
            assert p.returncode == 0, p.stderr
            with h5py.File(end, "r") as f:
                x = f["nodes/position"][:]
                assert int(f["state/scalars"][0]) == TOTAL
            assert x.shape == x_ref.shape and np.array_equal(x, x_ref), \
                f"{name} at step {done}: the continued run differs from the reference"
            print(f"  {name} at step {done}: exit 130, state written, continued bit-identically")
            stopped += 1
        assert stopped > 0, "every run ended before its signal: nothing was tested"
    print(f"signal stop: ok ({stopped} runs stopped and continued)")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""SIGKILL at any moment, even while a checkpoint is being written, leaves a readable
checkpoint: the periodic checkpoint is written to a temporary file, synced and renamed over
the old one, so the file of that name is always a whole checkpoint. A run that writes a
checkpoint every few milliseconds is killed at 20 random moments (seeded); after each kill
the checkpoint must open, hold finite positions and a step count the run reached, and a
restart from it must end bit-identically where a run that was never killed ends."""
import os
import random
import signal
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
DECK = os.path.join(HERE, "scene.lua")
KILLS = 20
EVERY = 50  # steps between checkpoints: about one per millisecond of this small scene


def deck(slender, *variables):
    args = [slender, DECK, "-log", "none", "-v", "speed=0.002"]
    for v in variables:
        args += ["-v", v]
    return args


def main():
    slender = sys.argv[1]
    rng = random.Random(20261204)
    with tempfile.TemporaryDirectory() as tmp:
        # how long the run takes decides the total: the kills must land inside it
        total = 100000
        ref = os.path.join(tmp, "reference.h5")
        t0 = time.monotonic()
        p = subprocess.run(deck(slender, f"steps={total}", "file=" + ref,
                                f"checkpoint_every={EVERY}"),
                           cwd=tmp, capture_output=True, text=True, timeout=600)
        wall = time.monotonic() - t0
        assert p.returncode == 0, p.stderr
        with h5py.File(ref, "r") as f:
            x_ref = f["nodes/position"][:]
        ok = 0
        mid_write = 0
        for k in range(KILLS):
            work = os.path.join(tmp, f"kill{k}")
            os.mkdir(work)
            moment = rng.uniform(0.0, 0.6 * wall)
            for attempt in range(4):
                # a machine less loaded than during the reference run may finish first:
                # then the same kill comes earlier
                for name in os.listdir(work):
                    os.remove(os.path.join(work, name))
                proc = subprocess.Popen(deck(slender, f"steps={total}", "file=never.h5",
                                             f"checkpoint_every={EVERY}"),
                                        cwd=work, stdout=subprocess.DEVNULL,
                                        stderr=subprocess.DEVNULL)
                # wait for the first checkpoint, then kill at a random moment of the rest
                ckpt = os.path.join(work, "periodic.h5")
                deadline = time.monotonic() + 60
                while (not os.path.exists(ckpt) and proc.poll() is None
                       and time.monotonic() < deadline):
                    time.sleep(0.002)
                time.sleep(moment)
                proc.send_signal(signal.SIGKILL)
                proc.wait(timeout=60)
                if proc.returncode == -signal.SIGKILL:
                    break
                moment /= 2
            assert proc.returncode == -signal.SIGKILL, \
                f"kill {k}: the run ended before the kill (exit {proc.returncode}); lengthen it"
            try:
                with h5py.File(ckpt, "r") as f:
                    done = int(f["state/scalars"][0])
                    assert np.isfinite(f["nodes/position"][:]).all(), "non-finite positions"
            except Exception as e:  # noqa: BLE001 - any failure to read is the finding
                raise AssertionError(f"kill {k}: the checkpoint left behind is unreadable: {e}")
            assert 0 < done < total and done % EVERY == 0, (k, done)
            leftovers = sorted(n for n in os.listdir(work) if n != "periodic.h5")
            end = os.path.join(work, "end.h5")
            p = subprocess.run(deck(slender, "mode=read", "file=" + ckpt,
                                    f"steps={total - done}", "out=" + end),
                               cwd=work, capture_output=True, text=True, timeout=600)
            assert p.returncode == 0, f"kill {k}: restart from step {done} failed: {p.stderr}"
            with h5py.File(end, "r") as f:
                x = f["nodes/position"][:]
                assert int(f["state/scalars"][0]) == total
            assert x.shape == x_ref.shape and np.array_equal(x, x_ref), \
                f"kill {k} at checkpoint step {done}: the continued run differs from the reference"
            print(f"  kill {k + 1:2d}: checkpoint of step {done} readable, restart bit-identical"
                  + (f" (left behind: {', '.join(leftovers)})" if leftovers else ""))
            ok += 1
            mid_write += "periodic.h5.tmp" in leftovers
    print(f"kill safety: ok ({ok} of {KILLS} kills left a readable checkpoint and a "
          f"bit-identical restart; {mid_write} of them struck while a checkpoint "
          f"was being written; reference run {wall:.2f} s)")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""scripts/long_run.sh carries a run across machines: `init` writes the run's
run.conf in the runs folder outside the repository ($SLENDER_RUNS or --dir), a segment
cut off (here: a stand-in binary that writes a checkpoint and fails) is saved into
<runs>/<name>/, a fresh work folder (another machine, $SLENDER_WORK) continues from the
stored checkpoint and thermo rows, each segment's steps and node-steps add up in
segments.csv, and a run that ended by itself is marked finished and not started again;
nothing is written into the repository."""
import csv
import json
import os
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# Stand-in for slender: 10 thermo rows per segment (a million steps each, nodes = 5 +
# step/1e6), printed on the console as the engine does (%14.7g: 1.3e+07), a checkpoint
# holding the last step; the first segment dies after its checkpoint.
FAKE = """#!{python}
import sys
args = sys.argv[1:]
restart = [a.split("=", 1)[1] for a in args if a.startswith("restart=")]
start = int(open(restart[0]).read()) if restart else 0
if restart:
    # as the engine does: drop the thermo rows past the checkpoint
    rows = [r for r in open("demo_thermo.csv").read().splitlines()[1:] if int(r.split(",")[0]) <= start]
else:
    rows = []
with open("demo_thermo.csv", "w") as fh:
    fh.write("step,feed.phi,count.nodes\\n")
    for r in rows:
        fh.write(r + "\\n")
    for k in range(0, 11):
        step = start + 1000000 * k
        # the checkpoint's own row is on the console, and already in the file
        if not (restart and k == 0):
            fh.write(f"{{step}},{{step / 1e8}},{{5 + step // 1000000}}\\n")
        print(f"{{step:14.7g}} {{step / 1e8:14.7g}} {{5 + step // 1000000:14.7g}}")
        if step == start + 6000000:
            open("demo_restart.h5", "w").write(str(step))
if not restart:
    sys.exit(3)  # cut off: the rows after step 600 are redone by the next segment
print("RESULT case=demo/x phi=0.25 steps=%d" % (start + 10000000))
"""


def sh(*args, env):
    return subprocess.run(["bash", os.path.join(ROOT, "scripts", "long_run.sh"), *args],
                          capture_output=True, text=True, env=env)


def main():
    with tempfile.TemporaryDirectory() as tmp:
        repo = os.path.join(tmp, "repo")
        os.makedirs(os.path.join(repo, "scripts"))
        os.makedirs(os.path.join(repo, "examples"))
        shutil.copy(os.path.join(ROOT, "scripts", "long_run.sh"), os.path.join(repo, "scripts"))
        open(os.path.join(repo, "examples", "demo.lua"), "w").write("-- stand-in\n")
        fake = os.path.join(tmp, "fake_slender")
        with open(fake, "w") as fh:
            fh.write(FAKE.format(python=sys.executable))
        os.chmod(fake, 0o755)
        script = [os.path.join(repo, "scripts", "long_run.sh")]
        runs = os.path.join(tmp, "runs")
        env = dict(os.environ, SLENDER_BIN=fake, SLENDER_RUNS=runs,
                   SLENDER_WORK=os.path.join(tmp, "machine1"))

        def run(*args, env=env):
            return subprocess.run(["bash", *script, *args], capture_output=True, text=True, env=env)

        out = run("init", "demo", "examples/demo.lua", "-v", "checkpoint_every=6000000")
        assert out.returncode == 0, (out.stdout, out.stderr)
        store = os.path.join(runs, "demo")
        conf = open(os.path.join(store, "run.conf")).read()
        assert "DECK=examples/demo.lua\nOUT=demo\nARGS=\"-v checkpoint_every=6000000\"" in conf, conf
        out = run("start", "demo")
        assert out.returncode == 3, (out.stdout, out.stderr)  # the cut-off segment
        assert run("save", "demo").returncode == 0
        assert open(os.path.join(store, "restart.h5")).read() == "6000000"
        assert not os.path.exists(os.path.join(store, "finished"))
        # another machine: nothing in its work folder but what the repository holds
        env2 = dict(env, SLENDER_WORK=os.path.join(tmp, "machine2"))
        out = run("start", "demo", env=env2)
        assert out.returncode == 0, (out.stdout, out.stderr)
        assert "restart=demo_restart.h5" in out.stdout, out.stdout
        assert run("save", "demo", env=env2).returncode == 0
        with open(os.path.join(store, "thermo.csv")) as fh:
            steps = [int(r["step"]) for r in csv.DictReader(fh)]
        assert steps == list(range(0, 17000000, 1000000)), steps  # one row per step, in order
        with open(os.path.join(store, "segments.csv")) as fh:
            segs = list(csv.DictReader(fh))
        # both segments, the first one's steps past its checkpoint included (they cost time)
        assert [(int(s["start_step"]), int(s["end_step"])) for s in segs] == \
            [(0, 10000000), (6000000, 16000000)], segs
        # node-steps of the second segment: rows 7e6 ... 16e6, 1e6 steps each at 5 + step/1e6 nodes
        assert int(segs[1]["node_steps"]) == sum(1000000 * (5 + k) for k in range(7, 17)), segs
        assert os.path.exists(os.path.join(store, "finished"))
        # the deck's RESULT line, as JSON
        with open(os.path.join(store, "result.json")) as fh:
            assert json.load(fh) == {"case": "demo/x", "phi": 0.25, "steps": 16000000}
        # a finished run is not started again
        out = run("start", "demo", env=dict(env, SLENDER_WORK=os.path.join(tmp, "machine3")))
        assert out.returncode == 1 and "has finished" in out.stderr, (out.stdout, out.stderr)
        # --dir names the runs folder instead of $SLENDER_RUNS
        env_nodir = {k: v for k, v in env.items() if k != "SLENDER_RUNS"}
        out = run("--dir", runs, "status", env=env_nodir)
        assert out.returncode == 0 and out.stdout.startswith("demo: finished"), (out.stdout, out.stderr)
        # the repository holds only what was copied into it
        assert sorted(os.listdir(repo)) == ["examples", "scripts"], os.listdir(repo)
    print("long_run: ok")


if __name__ == "__main__":
    main()

"""python3 -m slender: the run record a workflow rule reads, its exit status, info, render."""
import json
import os
import signal
import subprocess
import sys
import time

from conftest import PYTHON_DIR, deck


def cli(binary, *args, **kw):
    env = dict(os.environ, PYTHONPATH=PYTHON_DIR, SLENDER_BIN=binary)
    return subprocess.run([sys.executable, "-m", "slender", *args], env=env, capture_output=True,
                          text=True, timeout=60, **kw)


def test_run_writes_the_record(binary, tmp_path):
    out = tmp_path / "sub" / "r.json"
    p = cli(binary, "run", deck("chains2d.lua"), "-v", "steps=40", "-v", "every=20", "-t", "1",
            "--json", str(out))
    assert p.returncode == 0, p.stderr
    rec = json.loads(out.read_text())
    assert {"status", "returncode", "wall_s", "variables", "result", "results", "error"} <= set(rec)
    assert rec["status"] == "ok" and rec["returncode"] == 0 and rec["error"] == ""
    assert rec["variables"] == {"steps": "40", "every": "20"}
    assert rec["result"]["steps"] == 40 and isinstance(rec["result"]["tip_x"], float)
    assert len(rec["results"]) == 2 and rec["run_dir"] is None
    assert not os.path.exists(str(out) + ".tmp")


def test_run_of_a_failing_deck_exits_nonzero_with_its_error(binary, tmp_path):
    out = tmp_path / "r.json"
    p = cli(binary, "run", deck("bad_key.lua"), "--json", str(out))
    assert p.returncode == 1
    rec = json.loads(out.read_text())
    assert rec["status"] == "failed" and rec["returncode"] == 1
    assert "bad_key.lua:6:" in rec["error"] and "bad_key.lua:6:" in p.stderr


def test_run_timeout_and_keep(binary, tmp_path):
    keep = tmp_path / "run"
    p = cli(binary, "run", deck("chains2d.lua"), "-v", "steps=1000000000", "-v", "every=1000000",
            "--timeout", "2", "--keep", str(keep))
    assert p.returncode == 1
    rec = json.loads(p.stdout)                                 # no --json: on stdout
    assert rec["status"] == "timeout" and rec["run_dir"] == str(keep)
    assert (keep / "chains2d.h5").is_file() and (keep / "slender_interrupted.h5").is_file()


def test_sigterm_to_the_cli_stops_the_deck(binary, tmp_path):
    """A cancelled workflow job must not leave the deck running."""
    keep = tmp_path / "run"
    env = dict(os.environ, PYTHONPATH=PYTHON_DIR, SLENDER_BIN=binary)
    proc = subprocess.Popen([sys.executable, "-m", "slender", "run", deck("chains2d.lua"), "-v",
                             "steps=1000000000", "-v", "every=1000000", "--keep", str(keep)],
                            env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 20
    while not (keep / "chains2d.h5").exists() and time.monotonic() < deadline:
        time.sleep(0.05)
    time.sleep(0.2)
    proc.send_signal(signal.SIGTERM)
    assert proc.wait(timeout=20) == 128 + signal.SIGTERM
    proc.communicate()
    # the deck got the signal too: it wrote its interrupt checkpoint and ended
    assert (keep / "slender_interrupted.h5").is_file()


def test_info_describes_each_kind(binary, chains_run, plate_run):
    p = cli(binary, "info", os.path.join(chains_run.run_dir, "chains2d.h5"))
    assert p.returncode == 0
    assert "H5MD trajectory, 2D, 5 frames" in p.stdout
    assert "last frame: 2 chains, 22 nodes (12, 10 closed)" in p.stdout
    assert "fields: position, velocity" in p.stdout
    p = cli(binary, "info", os.path.join(plate_run.run_dir, "plate.h5"))
    assert "shell surface, 4 frames, 25 vertices, 32 triangles" in p.stdout
    assert "face fields: koiter.Ub" in p.stdout
    p = cli(binary, "info", os.path.join(chains_run.run_dir, "end.h5"))
    assert "checkpoint, 2D, step 200" in p.stdout and "chain ring: 10 nodes, closed" in p.stdout
    p = cli(binary, "info", deck("busy.lua"))
    assert p.returncode == 2 and "error" in p.stderr


def test_render(binary, chains_run, tmp_path):
    p = cli(binary, "render", os.path.join(chains_run.run_dir, "chains2d.h5"), str(tmp_path / "f.png"),
            "--frame", "0", "--radius", "10")
    assert p.returncode == 0 and "step 0" in p.stdout
    assert (tmp_path / "f.png").stat().st_size > 1000


def test_running_decks_needs_neither_numpy_nor_h5py(binary, tmp_path):
    """A workflow node with a bare python3 can still run decks."""
    out = tmp_path / "r.json"
    code = ("import runpy, sys\n"
            "sys.modules['numpy'] = sys.modules['h5py'] = sys.modules['matplotlib'] = None\n"
            f"sys.argv = ['slender', 'run', {deck('chains2d.lua')!r}, '-v', 'steps=10', '--json', {str(out)!r}]\n"
            "runpy.run_module('slender', run_name='__main__')\n")
    env = dict(os.environ, PYTHONPATH=PYTHON_DIR, SLENDER_BIN=binary)
    p = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=60)
    assert p.returncode == 0, p.stderr
    assert json.loads(out.read_text())["result"]["steps"] == 10

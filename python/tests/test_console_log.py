"""The console copy every run writes (slender -log, like LAMMPS's log.lammps) and the
end-of-run summary in it."""
import os
import subprocess

from conftest import deck


def slender(binary, *args, cwd):
    return subprocess.run([binary, *args], cwd=cwd, capture_output=True, text=True, timeout=60)


def test_the_log_is_the_console_with_the_command_on_top(binary, tmp_path):
    p = slender(binary, deck("chains2d.lua"), "-v", "steps=40", "-v", "every=20", "-log", "run.log",
                cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    log = (tmp_path / "run.log").read_text()
    head = [line for line in log.splitlines() if line.startswith("# ")]
    assert head[0].startswith("# slender ") and "chains2d.lua -v steps=40 -v every=20 -log run.log" in head[0]
    assert head[1].startswith("# started ")
    body = "".join(line + "\n" for line in log.splitlines() if not line.startswith("# "))
    assert body == p.stdout + p.stderr and "RESULT" in body
    assert not (tmp_path / "log.slender").exists()


def test_the_run_summary_names_the_time_of_each_stage(binary, tmp_path):
    p = slender(binary, deck("chains2d.lua"), "-v", "steps=300", "-v", "every=100", cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    summary = [line for line in p.stdout.splitlines() if line.startswith("run summary:")]
    assert len(summary) == 1 and "300 steps in" in summary[0] and "node-steps/s (22 nodes" in summary[0]
    stages = p.stdout.splitlines()[p.stdout.splitlines().index(summary[0]) + 1]
    assert stages.startswith("  time by stage:")
    shares = dict(part.strip().rsplit(" ", 1) for part in stages.split(":", 1)[1].split(";") if part.strip())
    assert "bond spring" in shares and "integrator and the rest" in shares
    assert 0 < sum(float(v.rstrip("%")) for v in shares.values()) <= 100.5
    # the default log file, here
    assert "run summary:" in (tmp_path / "log.slender").read_text()


def test_no_log_and_a_log_that_cannot_be_written(binary, tmp_path):
    p = slender(binary, deck("chains2d.lua"), "-v", "steps=10", "-log", "none", cwd=tmp_path)
    assert p.returncode == 0 and "chains2d.h5" in os.listdir(tmp_path)
    assert not (tmp_path / "log.slender").exists()
    p = slender(binary, deck("chains2d.lua"), "-log", str(tmp_path / "no" / "such" / "dir.log"), cwd=tmp_path)
    assert p.returncode == 2 and "cannot create log file" in p.stderr and "dir.log" in p.stderr


def test_a_deck_error_reaches_the_log(binary, tmp_path):
    p = slender(binary, deck("bad_key.lua"), "-log", "bad.log", cwd=tmp_path)
    assert p.returncode == 1 and "bad_key.lua:6:" in p.stderr
    assert "bad_key.lua:6:" in (tmp_path / "bad.log").read_text()

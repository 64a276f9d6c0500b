"""slender.run: RESULT parsing, and real runs that succeed, fail, print no result or
outlive their timeout."""
import os
import shutil

import numpy as np
import pytest
from conftest import EXAMPLES, deck

from slender import io, run


def test_result_lines_are_parsed_with_types():
    text = "\n".join([
        "step 1 of 2",
        "RESULT n=12 x=-2.5e-3 name=two words flag=true big=1_0 bad=nan",
        "RESULTS n=3",                      # not a RESULT line
        "  RESULT n=13 extra=1",            # later lines win in the merged dict
    ])
    results = run.parse_results(text)
    assert len(results) == 2
    first = results[0]
    assert first["n"] == 12 and isinstance(first["n"], int)
    assert first["x"] == -2.5e-3
    assert first["name"] == "two words"     # a string value with a space stays whole
    assert first["flag"] == "true" and first["big"] == "1_0"
    assert np.isnan(first["bad"])
    assert run.parse_result_text(text)[0]["x"] == "-2.5e-3"  # verbatim


def test_variables_are_formatted_as_the_binary_reads_them():
    assert run.format_variables({"a": 1, "b": True, "c": 0.5}) == {"a": "1", "b": "true", "c": "0.5"}
    assert run.format_variables(["a=1", ("b", "x=y")]) == {"a": "1", "b": "x=y"}
    with pytest.raises(ValueError):
        run.format_variables(["novalue"])


def test_a_run_reports_every_result_line(binary):
    res = run.run_deck(deck("chains2d.lua"), {"steps": 120, "every": 40}, binary=binary, timeout=60)
    assert res.status == "ok" and res.returncode == 0 and res.error == ""
    assert len(res.results) == 2                     # the deck prints two RESULT lines
    assert res.result["steps"] == 120                # the variable reached the deck
    assert res.result["label"] == "two chains"
    assert {"tip_x", "ring_x"} <= set(res.result)    # merged from both lines
    assert res.variables == {"steps": "120", "every": "40"}
    assert res.command[:4] == [binary, "-t", "1", "-q"]
    assert res.run_dir is None and res.wall_s > 0


def test_a_temporary_run_folder_is_removed_unless_kept(binary):
    kept = run.run_deck(deck("chains2d.lua"), {"steps": 10}, binary=binary, keep=True, timeout=60)
    try:
        assert kept.ok and os.path.isfile(os.path.join(kept.run_dir, "chains2d.h5"))
    finally:
        shutil.rmtree(kept.run_dir)


def test_a_run_in_a_given_folder_writes_there(binary, tmp_path):
    res = run.run_deck(deck("chains2d.lua"), {"steps": 10, "checkpoint": "end.h5"}, cwd=tmp_path / "w",
                       binary=binary, timeout=60)
    assert res.ok and res.run_dir == str(tmp_path / "w")
    # relative paths in variables are relative to the run folder
    assert io.read_checkpoint(tmp_path / "w" / "end.h5").step == 10


def test_a_deck_error_is_reported_with_its_line(binary):
    res = run.run_deck(deck("bad_key.lua"), binary=binary, timeout=60)
    assert res.status == "failed" and res.returncode == 1
    assert "bad_key.lua:6:" in res.error and "unknown key 'stiffnes'" in res.error, res.error
    assert res.results == [] and res.result == {}


def test_a_deck_without_result_line(binary):
    res = run.run_deck(os.path.join(EXAMPLES, "tutorial", "tip_loaded_wire.lua"), binary=binary, timeout=60)
    assert res.status == "no-result" and res.returncode == 0
    assert "tip at" in res.stdout


def test_a_timeout_stops_the_run_cleanly(binary):
    """SIGTERM at the timeout: the run finishes its step, writes a last frame and a
    checkpoint of that step, and exits 130."""
    res = run.run_deck(deck("chains2d.lua"), {"steps": 10 ** 9, "every": 10 ** 6}, binary=binary,
                       timeout=2.0, keep=True)
    try:
        assert res.status == "timeout" and res.returncode == 130, (res.status, res.returncode, res.stderr)
        assert res.error == "timeout after 2 s"
        ckpt = io.read_checkpoint(os.path.join(res.run_dir, "slender_interrupted.h5"))
        with io.Trajectory(os.path.join(res.run_dir, "chains2d.h5")) as t:
            assert ckpt.step > 0 and t.steps[-1] == ckpt.step
    finally:
        shutil.rmtree(res.run_dir)


def test_a_deck_deaf_to_sigterm_is_killed(binary, monkeypatch):
    monkeypatch.setattr(run, "TERMINATE_GRACE_S", 0.3)
    res = run.run_deck(deck("busy.lua"), binary=binary, timeout=0.3)
    assert res.status == "timeout" and res.returncode == -9
    assert res.wall_s < 10


def test_a_missing_binary_is_a_failed_run(tmp_path):
    res = run.run_deck(deck("chains2d.lua"), binary=str(tmp_path / "no-slender"))
    assert res.status == "failed" and res.returncode is None and "cannot run" in res.error


def test_the_binary_comes_from_the_argument_then_the_environment(monkeypatch):
    monkeypatch.setenv("SLENDER_BIN", "/opt/env/slender")
    assert run.find_binary("/opt/arg/slender") == "/opt/arg/slender"
    assert run.find_binary() == "/opt/env/slender"
    monkeypatch.delenv("SLENDER_BIN")
    monkeypatch.setattr(run, "REPO", run.Path("/nonexistent"))
    monkeypatch.setenv("PATH", "")
    with pytest.raises(FileNotFoundError):
        run.find_binary()

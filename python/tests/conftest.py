"""Shared fixtures: the package from this checkout, the binary, and dumps made by real runs.

The binary is the one slender.run.find_binary picks ($SLENDER_BIN, else build/slender,
else PATH); without one the tests that run decks are skipped. Runs that several tests
read are made once per session, each in its own folder."""
import os
import sys

import pytest

PYTHON_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, PYTHON_DIR)

from slender import run  # noqa: E402

REPO = os.path.dirname(PYTHON_DIR)
DECKS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "decks")
EXAMPLES = os.path.join(REPO, "examples")


def deck(name):
    """A test deck of this folder."""
    return os.path.join(DECKS, name)


@pytest.fixture(scope="session")
def binary():
    try:
        path = run.find_binary()
    except FileNotFoundError as e:
        pytest.skip(str(e))
    if os.path.sep in path and not os.access(path, os.X_OK):
        pytest.skip(f"slender binary {path} is not executable")
    return path


def _kept_run(factory, binary, name, deck_path, variables):
    res = run.run_deck(deck_path, variables, cwd=factory.mktemp(name), binary=binary, timeout=60)
    assert res.status == "ok", (res.status, res.error, res.stderr[-2000:])
    return res


@pytest.fixture(scope="session")
def chains_run(tmp_path_factory, binary):
    """chains2d.lua, 200 steps, a frame every 50, a checkpoint at the end."""
    return _kept_run(tmp_path_factory, binary, "chains2d", deck("chains2d.lua"),
                     {"steps": 200, "every": 50, "checkpoint": "end.h5"})


@pytest.fixture(scope="session")
def crumple_run(tmp_path_factory, binary):
    """The classic 2D crumpling deck in fast mode, stopped early: a wire grown by injection
    at both channels, so its nodes are not stored in chain order."""
    return _kept_run(tmp_path_factory, binary, "crumple", os.path.join(EXAMPLES, "crumple2d", "classic.lua"),
                     {"fast": 1, "max_phi": 0.1, "checkpoint_every": 10 ** 9})


@pytest.fixture(scope="session")
def pack_run(tmp_path_factory, binary):
    """The 3D packing deck in fast mode, stopped early: a rod fed through a nozzle."""
    return _kept_run(tmp_path_factory, binary, "pack3d", os.path.join(EXAMPLES, "pack3d", "low_torsion.lua"),
                     {"fast": 1, "max_phi": 0.2, "checkpoint_every": 10 ** 9})


@pytest.fixture(scope="session")
def plate_run(tmp_path_factory, binary):
    """plate.lua: a loaded plate, 60 steps, a shell frame every 20."""
    return _kept_run(tmp_path_factory, binary, "plate", deck("plate.lua"), {"steps": 60, "every": 20})

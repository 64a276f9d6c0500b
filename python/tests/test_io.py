"""slender.io on dumps of real runs: frames at the deck's interval, chains in chain order
(also for wires grown by injection), positions equal to what the deck reported, shell
meshes, checkpoints."""
import os

import h5py
import numpy as np
import pytest
from conftest import deck

from slender import io, run


def test_chains_from_edges_splits_orders_and_closes():
    edges = [[5, 3], [3, 1], [1, 0], [0, 2],   # an open chain, nodes not in storage order
             [6, 7], [7, 8], [8, 6],           # a ring
             [9, 4],                           # a chain of two nodes
             [0, 0], [0, 0]]                   # padding rows
    nodes, closed = io.chains_from_edges(edges)
    assert [list(n) for n in nodes] == [[5, 3, 1, 0, 2], [6, 7, 8], [9, 4]]
    assert closed == [False, True, False]
    assert io.chains_from_edges(np.zeros((4, 2))) == ([], [])


def test_frames_follow_the_dump_interval(binary, tmp_path):
    res = run.run_deck(deck("chains2d.lua"), {"steps": 130, "every": 40}, cwd=tmp_path, binary=binary,
                       timeout=60)
    assert res.ok
    with io.Trajectory(tmp_path / "chains2d.h5") as t:
        assert len(t) == 4                                   # steps 0, 40, 80, 120; not 130
        assert list(t.steps) == [0, 40, 80, 120]
        np.testing.assert_allclose(t.times, 0.01 * t.steps)  # the deck's dt
        assert t.dimension == 2 and t.fields == ["position", "velocity"]


def test_chains_hold_the_positions_the_deck_reported(chains_run):
    r = chains_run.result
    with io.Trajectory(os.path.join(chains_run.run_dir, "chains2d.h5")) as t:
        assert len(t) == 5 and t.steps[-1] == r["steps"]
        arm, ring = t.frame(-1)
        assert arm.shape == (12, 2) and ring.shape == (10, 2)
        assert t.closed(-1) == [False, True]
        assert sum(map(len, t.frame(-1))) == r["nodes"]
        # RESULT prints 10 significant digits
        np.testing.assert_allclose(arm[-1], [r["tip_x"], r["tip_y"]], rtol=1e-9)
        np.testing.assert_allclose(ring[3], [r["ring_x"], r["ring_y"]], rtol=1e-9)
        arm_nodes = t.chains(-1)[0][0]
        assert arm_nodes[-1] == r["tip"] - 1                  # the deck's index is 1-based
        velocities = t.frame(-1, "velocity")
        assert [v.shape for v in velocities] == [(12, 2), (10, 2)]
        assert np.abs(velocities[0][0]).max() == 0.0          # the clamped root
        assert np.abs(velocities[0][-1]).max() > 0.0          # the loaded tip moves
        with pytest.raises(KeyError):
            t.frame(0, "force")
        with pytest.raises(IndexError):
            t.frame(5)


def test_checkpoint_matches_the_last_frame(chains_run):
    ckpt = io.read_checkpoint(os.path.join(chains_run.run_dir, "end.h5"))
    assert ckpt.step == 200 and ckpt.dimension == 2 and ckpt.dt == 0.01
    assert len(ckpt.positions) == chains_run.result["nodes"]
    with io.Trajectory(os.path.join(chains_run.run_dir, "chains2d.h5")) as t:
        nodes, closed = t.chains(-1)
        assert ckpt.time == pytest.approx(t.times[-1])
        for (name, (ck_nodes, ck_closed)), tr_nodes, tr_closed, points in zip(
                ckpt.chains.items(), nodes, closed, t.frame(-1)):
            assert list(ck_nodes) == list(tr_nodes) and ck_closed == tr_closed, name
            np.testing.assert_array_equal(ckpt.chain_positions(name), points)


@pytest.mark.parametrize("fixture, chain", [("crumple_run", "wire"), ("pack_run", "rod")])
def test_an_injected_chain_reads_back_in_chain_order(request, fixture, chain):
    """Injection puts new nodes at the end of the arrays but at the front of the chain: the
    reader must follow the edges. Consecutive nodes sit one rest length apart."""
    res = request.getfixturevalue(fixture)
    name = res.result["case"].split("/")[1]
    ckpt = io.read_checkpoint(os.path.join(res.run_dir, f"{name}_restart.h5"))
    with io.Trajectory(os.path.join(res.run_dir, f"{name}.h5")) as t:
        assert t.steps[-1] == ckpt.step == res.result["steps"]
        (nodes,), (closed,) = t.chains(-1)
        assert not closed and len(nodes) == res.result["nodes"]
        assert np.any(np.diff(nodes) < 0), "storage order is chain order: nothing tested"
        assert list(nodes) == list(ckpt.chains[chain][0])
        (points,) = t.frame(-1)
        assert points.shape == (res.result["nodes"], t.dimension)
        lengths = np.linalg.norm(np.diff(points, axis=0), axis=1)
        np.testing.assert_allclose(lengths, ckpt.rest_lengths[chain], rtol=0.1)
        # the nodes in storage order would jump across the wire
        stored = np.asarray(t.file["particles/all/position/value"][-1])[np.sort(nodes)]
        assert np.linalg.norm(np.diff(stored, axis=0), axis=1).max() > 1.5 * lengths.max()


@pytest.mark.parametrize("fixture", ["crumple_run", "pack_run"])
def test_a_growing_trajectory_follows_h5md(request, fixture):
    """H5MD 1.1 on a run whose node count grows: id is the node index with fill value -1
    past each frame's count, observables/nodes is that count, edges past a frame's own read
    -1, box/dimension is a scalar, and connectivity/edges names its particles group by an
    object reference."""
    res = request.getfixturevalue(fixture)
    name = res.result["case"].split("/")[1]
    with io.Trajectory(os.path.join(res.run_dir, f"{name}.h5")) as t:
        f = t.file
        assert tuple(f["h5md"].attrs["version"]) == (1, 1)
        dim = f["particles/all/box"].attrs["dimension"]
        assert np.ndim(dim) == 0 and int(dim) == t.dimension
        ids = f["particles/all/id/value"]
        assert ids.dtype.kind == "i" and ids.fillvalue == -1
        # H5MD 1.1: a scalar per particle is [frames][particles], no component axis
        assert ids.ndim == 2 and f["particles/all/position/value"].ndim == 3
        counts = np.asarray(f["observables/nodes/value"])
        np.testing.assert_array_equal(f["observables/nodes/step"], f["particles/all/position/step"])
        assert counts[0] < counts[-1] == res.result["nodes"], "the wire did not grow: nothing tested"
        for k, n in enumerate(counts):
            row = np.asarray(ids[k])
            np.testing.assert_array_equal(row[:n], np.arange(n))
            assert np.all(row[n:] == -1)
        edges = f["connectivity/edges/value"]
        assert edges.fillvalue == -1
        first = np.asarray(edges[0])
        assert np.all(first[counts[0] - 1:] == -1) and np.all(first[:counts[0] - 1] >= 0)
        ref = f["connectivity/edges"].attrs["particles_group"]
        assert isinstance(ref, h5py.Reference) and f[ref].name == "/particles/all"


def test_the_walls_read_back_as_drawn(crumple_run, chains_run):
    """The crumpling deck's cavity (radius f = 10; its channel nodes are held, so the wall
    has no openings): one closed circle at every frame; a scene without walls has none."""
    with io.Trajectory(os.path.join(crumple_run.run_dir, "classic.h5")) as t:
        for i in (0, -1):
            (wall,) = t.walls(i)
            assert len(wall) > 100 and np.array_equal(wall[0], wall[-1])
            np.testing.assert_allclose(np.linalg.norm(wall[:, :2], axis=1), 10.0, rtol=1e-12)
    with io.Trajectory(os.path.join(chains_run.run_dir, "chains2d.h5")) as t:
        assert t.walls(0) == []


def test_shell_surface_frames(plate_run):
    r = plate_run.result
    with io.Surface(os.path.join(plate_run.run_dir, "plate.h5")) as s:
        assert list(s.steps) == [0, 20, 40, 60]
        assert np.all(np.diff(s.times) > 0)
        assert s.fields == ["koiter.Ub"]
        assert s.triangles.dtype.kind == "i" and s.triangles.shape == (r["triangles"], 3)
        vertices, triangles = s.mesh(0)
        assert vertices.shape == (r["nodes"], 3)
        assert triangles.min() == 0 and triangles.max() == r["nodes"] - 1
        assert np.all(vertices[:, 2] == 0.0)                 # the flat plate before the load
        assert np.all((vertices[:, :2] >= 0) & (vertices[:, :2] <= 1))
        assert np.all(s.face_field("koiter.Ub", 0) == 0.0)
        peaks = [s.vertices(i)[:, 2].max() for i in range(len(s))]
        assert np.all(np.diff(peaks) > 0)                     # the load (+z) bends it further
        ub = s.face_field("koiter.Ub", -1)
        assert ub.shape == (r["triangles"],) and ub.min() >= 0 and ub.max() > 0


def test_kind_and_open_dump(chains_run, plate_run, tmp_path):
    traj = os.path.join(chains_run.run_dir, "chains2d.h5")
    surf = os.path.join(plate_run.run_dir, "plate.h5")
    ckpt = os.path.join(chains_run.run_dir, "end.h5")
    assert [io.kind(p) for p in (traj, surf, ckpt)] == ["trajectory", "surface", "checkpoint"]
    with io.open_dump(traj) as t:
        assert isinstance(t, io.Trajectory)
    with io.open_dump(surf) as s:
        assert isinstance(s, io.Surface)
    assert isinstance(io.open_dump(ckpt), io.Checkpoint)
    other = tmp_path / "other.h5"
    with h5py.File(other, "w") as f:
        f["x"] = [1, 2]
    with pytest.raises(ValueError):
        io.kind(other)

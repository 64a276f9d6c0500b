"""slender.plot: the segments drawn, a wire where its data puts it, and PNGs of real dumps."""
import os

import matplotlib.image
import matplotlib.pyplot as plt
import numpy as np
import pytest

from slender import plot


def ink(png):
    """Share of pixels that are not white."""
    img = matplotlib.image.imread(png)[:, :, :3]
    return float(np.mean(img.min(axis=2) < 0.9))


def test_segments_join_consecutive_nodes_and_close_rings():
    line = np.array([[0, 0], [1, 0], [2, 0]], float)
    ring = np.array([[0, 5], [1, 5], [0, 6]], float)
    segs, values = plot.segments([line, ring], [False, True], [[0, 2, 4], [1, 1, 4]])
    assert segs.shape == (2 + 3, 2, 2)
    np.testing.assert_array_equal(segs[1], [[1, 0], [2, 0]])
    np.testing.assert_array_equal(segs[4], [[0, 6], [0, 5]])  # the ring's closing edge
    np.testing.assert_array_equal(values, [1, 3, 1, 2.5, 2.5])


def test_a_wire_is_drawn_where_its_coordinates_are(tmp_path):
    fig, ax = plt.subplots(figsize=(4, 4), dpi=100)
    chain = np.array([[-5.0, 0.0], [0.0, 0.0], [5.0, 0.0]])
    lc = plot.wire2d(ax, [chain], radius=8.0)
    plot.set_width_in_data_units(ax, lc, 0.5)
    fig.canvas.draw()
    height = fig.canvas.get_width_height()[1]

    def pixel(x, y):
        px, py = ax.transData.transform((x, y))
        return int(height - py), int(px)

    out = tmp_path / "wire.png"
    fig.savefig(out, dpi=100)
    plt.close(fig)
    img = matplotlib.image.imread(out)[:, :, :3]
    assert img[pixel(2.5, 0.0)].max() < 0.2           # on the wire: black
    assert img[pixel(2.5, 3.0)].min() > 0.9           # inside the cavity, off the wire: white
    assert img[pixel(0.0, -8.0)].max() < 0.6          # the cavity circle
    assert img[pixel(7.0, 0.0)].min() > 0.9           # past the wire's end


def test_render_a_2d_wire_and_a_3d_packing(chains_run, pack_run, tmp_path):
    step = plot.render_trajectory(os.path.join(chains_run.run_dir, "chains2d.h5"), tmp_path / "w.png",
                                  radius=12)
    assert step == 200 and ink(tmp_path / "w.png") > 0.01
    step = plot.render(os.path.join(pack_run.run_dir, "low_torsion.h5"), tmp_path / "p.png", field="bend.energy")
    assert step == pack_run.result["steps"] and ink(tmp_path / "p.png") > 0.01


def test_render_a_shell_surface(plate_run, tmp_path):
    path = os.path.join(plate_run.run_dir, "plate.h5")
    assert plot.render(path, tmp_path / "s.png", field="koiter.Ub") == 60
    assert plot.render(path, tmp_path / "flat.png", frame=0) == 0
    assert ink(tmp_path / "s.png") > 0.01 and ink(tmp_path / "flat.png") > 0.01
    with pytest.raises(ValueError):
        plot.render(path, tmp_path / "x.png", radius=1.0)


def test_a_checkpoint_has_nothing_to_render(chains_run, tmp_path):
    with pytest.raises(ValueError):
        plot.render(os.path.join(chains_run.run_dir, "end.h5"), tmp_path / "c.png")

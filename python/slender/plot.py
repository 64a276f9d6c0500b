"""Pictures of slender's dumps with matplotlib (Agg: no display needed).

Drawing functions take an axes and data (ordered chains from slender.io, or a mesh);
render_* functions read a dump and write a PNG.
"""

import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection, PatchCollection  # noqa: E402
from matplotlib.colors import Normalize  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection  # noqa: E402

from . import io  # noqa: E402


def segments(chains, closed=None, values=None):
    """The segments of ordered chains ([S, 2, dim]) and, with per-node values per chain,
    one value per segment (the mean of its two ends)."""
    closed = closed or [False] * len(chains)
    segs, seg_values = [], []
    for k, (points, ring) in enumerate(zip(chains, closed)):
        points = np.asarray(points, dtype=float)
        ends = np.roll(points, -1, axis=0) if ring else points[1:]
        starts = points if ring else points[:-1]
        segs.append(np.stack([starts, ends], axis=1))
        if values is not None:
            v = np.asarray(values[k], dtype=float).reshape(len(points))
            seg_values.append(0.5 * (v + np.roll(v, -1)) if ring else 0.5 * (v[:-1] + v[1:]))
    dim = segs[0].shape[2] if segs else 2
    segs = np.concatenate(segs) if segs else np.zeros((0, 2, dim))
    return segs, (np.concatenate(seg_values) if values is not None and seg_values else None)


def wire2d(ax, chains, closed=None, values=None, radius=None, center=(0.0, 0.0), norm=None,
           cmap="viridis", color="k", linewidth=1.0, margin=0.0):
    """Draw 2D chains as polylines (coloured by per-node values if given), the cavity
    circle of `radius` about `center`, with equal axes fitting both (and `margin` more
    around the wire: half its drawn width). Returns the LineCollection (see
    set_width_in_data_units for a wire drawn at its diameter)."""
    segs, seg_values = segments([np.asarray(c)[:, :2] for c in chains], closed, values)
    lc = LineCollection(segs, capstyle="round", joinstyle="round", linewidths=linewidth)
    if seg_values is not None:
        lc.set_array(seg_values)
        lc.set_cmap(cmap)
        lc.set_norm(norm or Normalize(0.0, seg_values.max() if len(seg_values) and seg_values.max() > 0 else 1.0))
    else:
        lc.set_color(color)
    ax.add_collection(lc)
    center = np.asarray(center, dtype=float)
    reach = float(np.max(np.linalg.norm(segs.reshape(-1, 2) - center, axis=1))) + margin if len(segs) else 1.0
    if radius is not None:
        ax.add_patch(plt.Circle(center, radius, fill=False, edgecolor="k", linewidth=1.2))
        reach = max(reach, radius)
    half = 1.04 * reach
    ax.set_xlim(center[0] - half, center[0] + half)
    ax.set_ylim(center[1] - half, center[1] + half)
    ax.set_aspect("equal", adjustable="box")
    return lc


def set_width_in_data_units(ax, collection, width):
    """Line width of `collection` equal to `width` data units (a wire at its diameter).
    Call it once the figure's layout is final (after colour bars)."""
    ax.apply_aspect()
    px = ax.transData.transform((1.0, 0.0))[0] - ax.transData.transform((0.0, 0.0))[0]
    collection.set_linewidth(width * px * 72.0 / ax.figure.dpi)


def packing3d(ax, chains, closed=None, values=None, radius=None, cmap="viridis", color="k",
              linewidth=2.0):
    """Draw 3D chains in a 3D axes (coloured by per-node values if given), in a cube of
    half side `radius` (else fitted to the chains). Returns the Line3DCollection."""
    segs, seg_values = segments(chains, closed, values)
    lc = Line3DCollection(segs, linewidths=linewidth)
    if seg_values is not None:
        lc.set_array(seg_values)
        lc.set_cmap(cmap)
    else:
        lc.set_color(color)
    ax.add_collection(lc)
    if radius is None:
        radius = float(np.abs(segs).max()) if len(segs) else 1.0
    ax.set_xlim(-radius, radius)
    ax.set_ylim(-radius, radius)
    ax.set_zlim(-radius, radius)
    ax.set_box_aspect((1, 1, 1))
    return lc


def section(ax, chains, rod_radius, z0=0.0, values=None, sphere_radius=None, cmap="viridis"):
    """A cut through a 3D packing at height z0: the nodes within rod_radius of the plane
    drawn as discs of the rod's radius (coloured by per-node values if given), and the
    sphere's circle at that height. Returns how many nodes the cut holds."""
    pts = np.concatenate([np.asarray(c, dtype=float) for c in chains]) if chains else np.zeros((0, 3))
    vals = np.concatenate([np.ravel(v) for v in values]) if values is not None and chains else None
    cut = np.abs(pts[:, 2] - z0) < rod_radius
    pc = PatchCollection([plt.Circle((x, y), rod_radius) for x, y in pts[cut, :2]], cmap=cmap,
                         edgecolor="k", linewidth=0.3)
    pc.set_array(vals[cut] if vals is not None else np.zeros(int(cut.sum())))
    ax.add_collection(pc)
    reach = sphere_radius if sphere_radius is not None else (float(np.abs(pts[:, :2]).max()) if len(pts) else 1.0)
    if sphere_radius is not None:
        ax.add_patch(plt.Circle((0, 0), math.sqrt(max(sphere_radius ** 2 - z0 ** 2, 0.0)), fill=False, color="k"))
    ax.set_xlim(-reach, reach)
    ax.set_ylim(-reach, reach)
    ax.set_aspect("equal")
    return int(cut.sum())


def surface(ax, vertices, triangles, face_colors=None, views=None):
    """Draw a triangle mesh in a 3D axes with equal scales (faces in `face_colors`, RGBA
    per triangle, else a flat blue). Returns the Poly3DCollection."""
    vertices = np.asarray(vertices, dtype=float)
    if face_colors is None:
        face_colors = np.full((len(triangles), 4), (0.6, 0.7, 0.9, 1.0))
    poly = Poly3DCollection(vertices[np.asarray(triangles)], facecolors=face_colors, edgecolor="k",
                            linewidths=0.05)
    ax.add_collection3d(poly)
    lo, hi = vertices.min(axis=0), vertices.max(axis=0)
    c, r = 0.5 * (lo + hi), max(0.5 * float((hi - lo).max()), 1e-12)
    for axis, set_lim in enumerate((ax.set_xlim, ax.set_ylim, ax.set_zlim)):
        set_lim(c[axis] - r, c[axis] + r)
    ax.set_box_aspect((1, 1, 1))
    ax.set_axis_off()
    return poly


def render_trajectory(path, out, frame=-1, radius=None, field=None, dpi=110):
    """A frame of an H5MD trajectory as a PNG: 2D wires inside the cavity circle of
    `radius`, 3D chains in perspective; coloured by a scalar per-node `field` (e.g.
    bend.energy) if given. Returns the frame's step."""
    with io.Trajectory(path) as t:
        chains, closed = t.frame(frame), t.closed(frame)
        walls = t.walls(frame)
        values = t.frame(frame, field) if field else None
        if values and values[0].ndim > 1 and values[0].shape[1] != 1:
            raise ValueError(f"{path}: {field} has {values[0].shape[1]} components; colours need one")
        step, time, dim = int(t.steps[frame]), float(t.times[frame]), t.dimension
    fig = plt.figure(figsize=(5.5, 5))
    if dim == 2:
        ax = fig.add_subplot(1, 1, 1)
        artist = wire2d(ax, chains, closed, values, radius=radius)
        # the walls as the dump drew them (openings and all), where no radius was given
        if radius is None and walls:
            ax.add_collection(LineCollection([w[:, :2] for w in walls], colors="k", linewidths=1.2))
            ax.autoscale()
            ax.set_aspect("equal")
    else:
        ax = fig.add_subplot(1, 1, 1, projection="3d")
        artist = packing3d(ax, chains, closed, values, radius=radius)
        if radius is None:
            for w in walls:
                ax.plot(w[:, 0], w[:, 1], w[:, 2], color="0.6", linewidth=0.6)
    if values is not None:
        fig.colorbar(artist, ax=ax, shrink=0.7, label=field)
    ax.set_title(f"{sum(len(c) for c in chains)} nodes, step {step}, t = {time:.6g}", fontsize=9)
    fig.savefig(out, dpi=dpi)
    plt.close(fig)
    return step


def log_or_linear(values, field):
    """Values as plotted: log10 for bending energy densities (U_b spans decades)."""
    return (np.log10(np.maximum(values, 1e-12)), f"log10 {field}") if "Ub" in field else (values, field)


def render_surface(path, out, frame=-1, field=None, dpi=130):
    """A frame of a shell surface dump as a PNG, seen from two directions, faces coloured
    by a per-face field (log10 for U_b) when given and present. Returns the step."""
    with io.Surface(path) as s:
        vertices, triangles = s.mesh(frame)
        values = s.face_field(field, frame) if field and field in s.fields else None
        step = int(s.steps[frame])
    fig = plt.figure(figsize=(10, 5))
    colors, norm = None, None
    if values is not None:
        values, label = log_or_linear(values, field)
        norm = plt.Normalize(np.percentile(values, 2), np.percentile(values, 98))
        colors = plt.cm.viridis(norm(values))
    for k, (elev, azim) in enumerate([(30, -60), (90, -90)]):
        ax = fig.add_subplot(1, 2, k + 1, projection="3d")
        surface(ax, vertices, triangles, colors)
        ax.view_init(elev=elev, azim=azim)
    if norm is not None:
        fig.colorbar(plt.cm.ScalarMappable(norm=norm, cmap="viridis"), ax=fig.axes, shrink=0.6, label=label)
    fig.savefig(out, dpi=dpi)
    plt.close(fig)
    return step


def render(path, out, frame=-1, field=None, radius=None):
    """Render any trajectory or shell surface dump to a PNG (render_trajectory or
    render_surface, whichever the file is); returns the frame's step."""
    k = io.kind(path)
    if k == "trajectory":
        return render_trajectory(path, out, frame, radius=radius, field=field)
    if k != "surface":
        raise ValueError(f"{path}: a {k} has no frames to render")
    if radius is not None:
        raise ValueError(f"{path}: a shell surface takes no radius")
    return render_surface(path, out, frame, field=field)


def thumbnail(path, out, radius=None, size_in=1.6, dpi=100):
    """A small picture of a run's final state (a checkpoint, or the last frame of a 2D
    trajectory): the wire as thin lines inside the cavity circle of `radius`, no axes. For
    the studies' grids of thumbnails (workflows/phase_diagram.smk)."""
    if io.kind(path) == "checkpoint":
        ck = io.read_checkpoint(path)
        if ck.dimension != 2:
            raise ValueError(f"{path}: thumbnails draw 2D wires")
        chains = [ck.chain_positions(name) for name in ck.chains]
        closed = [ck.chains[name][1] for name in ck.chains]
    else:
        with io.Trajectory(path) as t:
            if t.dimension != 2:
                raise ValueError(f"{path}: thumbnails draw 2D wires")
            chains, closed = t.frame(-1), t.closed(-1)
    fig = plt.figure(figsize=(size_in, size_in))
    ax = fig.add_axes([0, 0, 1, 1])
    wire2d(ax, chains, closed, radius=radius, linewidth=0.4)
    ax.set_axis_off()
    fig.savefig(out, dpi=dpi)
    plt.close(fig)


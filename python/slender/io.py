"""Read what slender writes: H5MD trajectories, shell surfaces and checkpoints (h5py only).

Trajectories (dump "h5md", styles/dump/h5md.cpp): /particles/all/<field>/{step,time,value}
with value [frames, max nodes, components] ([frames, max nodes] for a one-component field
such as mass or id, as H5MD 1.1 has it; older files keep a last axis of 1),
and /connectivity/edges/value [frames, max edges, 2], each chain's edges in chain order. Rows past a frame's own count are padding
(-1, the datasets' fill value; files written before 0.2 pad with an edge from a node to
itself). /particles/all/id holds the node index (-1 past the frame's count) and
/observables/nodes the count per frame. Nodes are stored in the order they were created, so a
chain that grew by injection is not contiguous: the edges give the chain order, and
Trajectory returns every frame as ordered chains. A chain without edges (one node) does
not appear.

Shell surfaces (dump "shell", styles/shell/dump_shell.cpp): /mesh/triangles [T, 3] and
/frames/{position,<field>}/{step,time,value}, position [frames, nodes, 3] (the limit
surface at the control nodes), per-face fields [frames, T] ([frames, T, 1] in older files); a '/' in a field's name
is stored as '|'.

Checkpoints (dump "checkpoint", src/checkpoint_h5.cpp): /state/scalars (step, time, dt,
forces valid, dimension, ...), /nodes/{position,velocity,force,mass}, /chains/<name>/
{nodes,rest_length,closed}, /properties/<name>.
"""

from dataclasses import dataclass

import h5py
import numpy as np

POSITION = "particles/all/position"
EDGES = "connectivity/edges"


def kind(path):
    """'trajectory', 'surface' or 'checkpoint': which slender writer made the file."""
    with h5py.File(path, "r") as f:
        return _kind(f, path)


def _kind(f, path):
    if POSITION in f and EDGES in f:
        return "trajectory"
    if "mesh/triangles" in f and "frames/position" in f:
        return "surface"
    if "state/scalars" in f and "nodes/position" in f:
        return "checkpoint"
    raise ValueError(f"{path}: not a slender trajectory, shell surface or checkpoint")


def open_dump(path):
    """A Trajectory, Surface or Checkpoint, whichever the file is."""
    return {"trajectory": Trajectory, "surface": Surface, "checkpoint": read_checkpoint}[kind(path)](path)


def chains_from_edges(edges):
    """(node index arrays in chain order, closed flags) from one frame's edge rows.

    Rows whose two ends are equal (padding) are dropped. A chain ends where an edge does
    not start at the previous edge's head; it is closed when its last edge returns to its
    first node."""
    edges = np.asarray(edges, dtype=np.int64).reshape(-1, 2)
    edges = edges[edges[:, 0] != edges[:, 1]]
    if len(edges) == 0:
        return [], []
    starts = np.flatnonzero(edges[1:, 0] != edges[:-1, 1]) + 1
    nodes, closed = [], []
    for chunk in np.split(edges, starts):
        ring = len(chunk) > 1 and chunk[-1, 1] == chunk[0, 0]
        nodes.append(chunk[:, 0].copy() if ring else np.append(chunk[:, 0], chunk[-1, 1]))
        closed.append(bool(ring))
    return nodes, closed


class _Series:
    """Frames of an h5py file opened for reading; a context manager."""

    def __init__(self, path):
        self.path = str(path)
        self.file = h5py.File(self.path, "r")

    def close(self):
        self.file.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __len__(self):
        return len(self.steps)

    def _index(self, i):
        n = len(self)
        if not -n <= i < n:
            raise IndexError(f"{self.path}: frame {i} out of range ({n} frames)")
        return i % n


class Trajectory(_Series):
    """An H5MD trajectory as frames of ordered chains.

    times, steps: one per frame; dimension: 2 or 3; fields: the per-node fields dumped
    (position first). Frames a running dump has written to only some of the series are
    not counted."""

    def __init__(self, path):
        super().__init__(path)
        f = self.file
        if POSITION not in f or EDGES not in f:
            self.close()
            raise ValueError(f"{self.path}: not an H5MD trajectory of slender (no {POSITION} "
                             f"and {EDGES})")
        n = min(f[POSITION + "/step"].shape[0], f[EDGES + "/value"].shape[0])
        self.steps = np.asarray(f[POSITION + "/step"][:n], dtype=np.int64)
        self.times = np.asarray(f[POSITION + "/time"][:n], dtype=float)
        self.dimension = int(np.ravel(f["particles/all/box"].attrs["dimension"])[0])  # scalar since 0.2
        group = f["particles/all"]
        self.fields = ["position"] + sorted(k for k in group if k not in ("position", "box", "id")
                                            and isinstance(group[k], h5py.Group) and "value" in group[k])

    def chains(self, i):
        """(node index arrays in chain order, closed flags) of frame i."""
        return chains_from_edges(self.file[EDGES + "/value"][self._index(i)])

    def frame(self, i, field="position"):
        """One array per chain of frame i, rows in chain order: positions (n x dimension),
        or any dumped per-node field (n x components)."""
        if field not in self.fields:
            raise KeyError(f"{self.path}: no field {field!r} (has {', '.join(self.fields)})")
        values = np.asarray(self.file[f"particles/all/{field}/value"][self._index(i)])
        if values.ndim == 1:  # one component: a row of one value each, as older files
            values = values[:, None]
        return [values[nodes] for nodes in self.chains(i)[0]]

    def closed(self, i):
        """Whether each chain of frame i is a ring."""
        return self.chains(i)[1]

    def walls(self, i):
        """The walls of frame i as the dump drew them (/xdmf/wall_points, wall_polylines: a
        circle broken at its openings, a sphere's three great circles), one point array per
        line; [] for a scene without walls or a file written before they were."""
        if "xdmf/wall_points" not in self.file or "xdmf/wall_polylines" not in self.file:
            return []
        step = self.steps[self._index(i)]
        frames = np.asarray(self.file["xdmf/wall_points/step"][()])
        k = np.flatnonzero(frames == step)
        if len(k) == 0:
            return []
        points = np.asarray(self.file["xdmf/wall_points/value"][k[0]])
        cells = np.asarray(self.file["xdmf/wall_polylines/value"][k[0]]).reshape(-1)
        lines, at = [], 0
        while at + 1 < len(cells) and cells[at] == 2:  # XDMF polyline: type, count, indices
            n = int(cells[at + 1])
            lines.append(points[cells[at + 2:at + 2 + n]])
            at += 2 + n
        return lines


class Surface(_Series):
    """A shell surface dump: one triangle mesh, vertex positions per frame.

    triangles: int array [T, 3] of vertex indices; times, steps: one per frame;
    fields: per-face field names as the deck wrote them (e.g. koiter.Ub)."""

    def __init__(self, path):
        super().__init__(path)
        f = self.file
        if "mesh/triangles" not in f or "frames/position" not in f:
            self.close()
            raise ValueError(f"{self.path}: not a shell surface of slender (no mesh/triangles "
                             "and frames/position)")
        # stored as doubles; exact for any vertex count a mesh can have
        self.triangles = np.asarray(f["mesh/triangles"][()]).astype(np.int64)
        n = f["frames/position/value"].shape[0]
        # a file made by hand may lack step and time: -1 and NaN then
        pos = f["frames/position"]
        self.steps = np.asarray(pos["step"][()], dtype=np.int64) if "step" in pos else np.full(n, -1)
        self.times = np.asarray(pos["time"][()], dtype=float) if "time" in pos else np.full(n, np.nan)
        self.fields = sorted(k.replace("|", "/") for k in f["frames"] if k != "position")

    def vertices(self, i):
        """Vertex positions of frame i, [nodes, 3]."""
        return np.asarray(self.file["frames/position/value"][self._index(i)], dtype=float)

    def mesh(self, i):
        """(vertices, triangles) of frame i."""
        return self.vertices(i), self.triangles

    def face_field(self, name, i):
        """One value per triangle of a per-face field (e.g. koiter.Ub) in frame i."""
        if name not in self.fields:
            raise KeyError(f"{self.path}: no face field {name!r} (has {', '.join(self.fields) or 'none'})")
        return np.asarray(self.file[f"frames/{name.replace('/', '|')}/value"][self._index(i)]).reshape(-1)


@dataclass
class Checkpoint:
    """The state a checkpoint holds: positions/velocities [N, dimension], masses [N],
    chains {name: (node indices in chain order, closed)}, rest lengths per chain, and
    the names of the node properties saved for the restart."""
    path: str
    step: int
    time: float
    dt: float
    dimension: int
    positions: np.ndarray
    velocities: np.ndarray
    masses: np.ndarray
    chains: dict
    rest_lengths: dict
    properties: list

    def chain_positions(self, name):
        """Positions of one chain's nodes in chain order."""
        return self.positions[self.chains[name][0]]


def read_checkpoint(path):
    """Read a checkpoint's state (not the styles' internal state)."""
    with h5py.File(path, "r") as f:
        if "state/scalars" not in f or "nodes/position" not in f:
            raise ValueError(f"{path}: not a slender checkpoint (no state/scalars and nodes/position)")
        s = np.asarray(f["state/scalars"][()], dtype=float)
        dim = int(s[4])
        chains, rest = {}, {}
        for name, g in f.get("chains", {}).items():
            chains[name] = (np.asarray(g["nodes"][()]).astype(np.int64), bool(g["closed"][0]))
            rest[name] = np.asarray(g["rest_length"][()], dtype=float)
        return Checkpoint(str(path), int(s[0]), float(s[1]), float(s[2]), dim,
                          np.asarray(f["nodes/position"][()])[:, :dim],
                          np.asarray(f["nodes/velocity"][()])[:, :dim],
                          np.asarray(f["nodes/mass"][()]), chains, rest,
                          sorted(f["properties"]) if "properties" in f else [])


def describe(path):
    """Lines saying what a dump holds (the `info` command)."""
    k = kind(path)
    if k == "checkpoint":
        c = read_checkpoint(path)
        lines = [f"{path}: checkpoint, {c.dimension}D, step {c.step}, time {c.time:.6g}, "
                 f"dt {c.dt:.6g}, {len(c.positions)} nodes"]
        for name, (nodes, closed) in c.chains.items():
            lines.append(f"  chain {name}: {len(nodes)} nodes{', closed' if closed else ''}")
        if c.properties:
            lines.append("  properties: " + ", ".join(c.properties))
        return lines
    if k == "trajectory":
        with Trajectory(path) as t:
            lines = [f"{path}: H5MD trajectory, {t.dimension}D, {len(t)} frames"]
            if len(t):
                lines.append(f"  steps {t.steps[0]} .. {t.steps[-1]}, time {t.times[0]:.6g} .. "
                             f"{t.times[-1]:.6g}")
                nodes, closed = t.chains(-1)
                lines.append(f"  last frame: {len(nodes)} chains, {sum(map(len, nodes))} nodes "
                             f"({', '.join(f'{len(n)}' + (' closed' if c else '') for n, c in zip(nodes, closed))})")
            lines.append("  fields: " + ", ".join(t.fields))
            return lines
    with Surface(path) as s:
        n = s.file["frames/position/value"].shape[1]
        lines = [f"{path}: shell surface, {len(s)} frames, {n} vertices, {len(s.triangles)} triangles"]
        if len(s):
            lines.append(f"  steps {s.steps[0]} .. {s.steps[-1]}, time {s.times[0]:.6g} .. {s.times[-1]:.6g}")
        lines.append("  face fields: " + (", ".join(s.fields) or "none"))
        return lines

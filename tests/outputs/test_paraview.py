"""ParaView opens every dump kind: run by ParaView's pvbatch (Debian's paraview and
python3-paraview), it writes the dumps of tests/outputs/dumps.lua with the slender binary
given as argv[1] and reads each .xdmf with ParaView's XDMF Reader, as a user would open it.

Checks: one polyline cell per chain with the chain's nodes in order (a closed chain ends on
its first node), the node fields, the walls' own file (the circle's arcs between its
openings, a sphere's three great circles), increasing times (a shell's frames written after
minimisations, at one clock reading, are shown as frames 0, 1, ...), triangles for shells.
Prints "paraview readers: ok"."""
import os
import subprocess
import sys
import tempfile

from paraview.simple import XDMFReader


def read_frames(path):
    reader = XDMFReader(FileNames=[path])
    times = list(reader.TimestepValues or [0.0])
    frames = []
    for t in times:
        reader.UpdatePipeline(t)
        frames.append(reader.GetClientSideObject().GetOutputDataObject(0))
    return times, frames


def cells(grid):
    out = []
    for c in range(grid.GetNumberOfCells()):
        ids = grid.GetCell(c).GetPointIds()
        out.append([ids.GetId(k) for k in range(ids.GetNumberOfIds())])
    return out


def check(cond, what):
    if not cond:
        sys.exit("paraview readers: FAILED: " + what)


def main():
    slender, deck = os.path.abspath(sys.argv[1]), os.path.join(os.path.dirname(
        os.path.abspath(__file__)), "dumps.lua")
    with tempfile.TemporaryDirectory() as tmp:
        for kind in ("wire2d", "wire3d", "shell"):
            subprocess.run([slender, "-q", deck, "-v", "kind=" + kind], cwd=tmp, check=True)
        # the ring (30 nodes, closed) and the open wire (8 nodes) at three times
        times, frames = read_frames(os.path.join(tmp, "wire2d.h5.xdmf"))
        check(times == [0.0, 0.05, 0.1], "wire2d times %s" % times)
        for grid in frames:
            lines = cells(grid)
            check(grid.GetNumberOfPoints() == 38, "wire2d points %d" % grid.GetNumberOfPoints())
            check([len(c) for c in lines] == [31, 8], "wire2d polylines %s" % lines)
            check(lines[0] == list(range(30)) + [0], "the ring is not one closed polyline")
            check(lines[1] == list(range(30, 38)), "the open wire is not in chain order")
            v = grid.GetPointData().GetArray("velocity")
            check(v is not None and v.GetNumberOfComponents() in (2, 3), "wire2d velocity field")
        # the walls: two arcs of the circle of radius 8 (openings on the x axis), at each time
        times, frames = read_frames(os.path.join(tmp, "wire2d.h5.walls.xdmf"))
        check(times == [0.0, 0.05, 0.1], "walls times %s" % times)
        for grid in frames:
            arcs = cells(grid)
            check(len(arcs) == 2 and all(len(a) > 100 for a in arcs), "wall arcs %s" % [len(a) for a in arcs])
            p = grid.GetPoint(arcs[0][len(arcs[0]) // 2])
            check(abs((p[0] ** 2 + p[1] ** 2) ** 0.5 - 8) < 1e-9, "wall point %s" % (p,))
        times, frames = read_frames(os.path.join(tmp, "wire3d.h5.walls.xdmf"))
        check([len(c) for c in cells(frames[-1])] == [257, 257, 257], "sphere's great circles")
        times, frames = read_frames(os.path.join(tmp, "wire3d.h5.xdmf"))
        check(len(times) == 3, "wire3d times %s" % times)
        lines = cells(frames[-1])
        check(lines == [list(range(12))], "wire3d polyline %s" % lines)
        f = frames[-1].GetPointData().GetArray("force")
        check(f is not None and f.GetNumberOfComponents() == 3, "wire3d force field")
        times, frames = read_frames(os.path.join(tmp, "shell.h5.xdmf"))
        check(times == [0.0, 1.0], "shell frames after minimisations: times %s" % times)
        for grid in frames:
            tris = cells(grid)
            check(len(tris) > 50 and all(len(t) == 3 for t in tris), "shell triangles")
            check(max(max(t) for t in tris) < grid.GetNumberOfPoints(), "shell triangle indices")
            check(grid.GetCellData().GetArray("koiter.Ub") is not None, "shell koiter.Ub field")
    print("paraview readers: ok")


if __name__ == "__main__":
    main()

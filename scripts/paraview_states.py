"""ParaView state files of the flagship scenes (run by ParaView's pvbatch): the wire or rod as
a tube of its own diameter coloured by a per-node field, the cavity walls as lines, the shell
coloured by its bending energy density; with the camera on the whole scene.

  /usr/bin/python3 scripts/paraview_states.py SLENDER [OUTDIR [--check]]

runs each scene's fast deck in a temporary folder
(the states need the data to set up their colours), builds the view on the files there and
saves examples/<scene>/<deck>.pvsm (or into OUTDIR). --check then loads each saved state
afresh in that folder, renders it to OUTDIR/<deck>.png and fails unless the picture shows the
wire or shell (enough pixels away from the background). The states name the files relative
to the folder ParaView is started in, so open one where the deck wrote its files, e.g.

  cd out && paraview --state=../examples/crumple2d/classic.pvsm
"""
import os
import subprocess
import sys
import tempfile
import time

try:  # in pvbatch (the --build and --render modes); the driver is plain Python
    from paraview.simple import (ColorBy, ExtractSurface, GetActiveViewOrCreate, GetAnimationScene,
                                 Hide, LoadState, Render, ResetSession, SaveScreenshot, SaveState,
                                 Show, Tube, XDMFReader)
except ImportError:
    pass

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# deck, its -v variables, the trajectory it writes, tube radius (half the wire's diameter or
# the rod's radius), the per-node field to colour by; shells: the surface and a face field
SCENES = [
    ("crumple2d", "classic", {"fast": 1}, "classic.h5", 0.5, "bend.plastic_curvature"),
    ("crumple2d", "plastic", {"fast": 1}, "plastic.h5", 0.5, "bend.plastic_curvature"),
    ("crumple2d", "spiral", {"fast": 1}, "spiral.h5", 0.5, "bend.plastic_curvature"),
    ("pack3d", "low_torsion", {"R": 4}, "low_torsion.h5", 1.0, "bend.energy"),
    ("pack3d", "high_torsion", {"R": 4}, "high_torsion.h5", 1.0, "bend.energy"),
    ("shells", "econe", {"fast": 1, "out": "."}, "surface.h5", None, "koiter.Ub"),
]


def run_deck(slender, scene, deck, variables, folder):
    cmd = [slender, "-q", "-log", "none", os.path.join(REPO, "examples", scene, deck + ".lua"),
           "-v", "plots=0"]
    for k, v in variables.items():
        cmd += ["-v", f"{k}={v}"]
    subprocess.run(cmd, cwd=folder, check=True, stdout=subprocess.DEVNULL)


def build_view(trajectory, radius, field, three_d=False):
    """The pipeline on `trajectory` (a name relative to the working folder)."""
    ResetSession()
    view = GetActiveViewOrCreate("RenderView")
    data = XDMFReader(registrationName=trajectory, FileNames=[trajectory + ".xdmf"])
    # the view at the last frame (the packed state): colours and camera are set on it
    scene = GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    scene.AnimationTime = max(data.TimestepValues or [0.0])
    if radius is None:  # a shell surface: faces coloured by the field
        shown = Show(data, view)
        ColorBy(shown, ("CELLS", field))
    else:
        # the XDMF reader gives an unstructured grid; the Tube filter takes polylines
        lines = ExtractSurface(registrationName="polylines", Input=data)
        tube = Tube(registrationName="wire", Input=lines)
        tube.Radius = radius
        tube.NumberofSides = 12
        Hide(data, view)
        shown = Show(tube, view)
        ColorBy(shown, ("POINTS", field))
        walls = trajectory + ".walls.xdmf"
        if os.path.exists(walls):
            wall = XDMFReader(registrationName="walls", FileNames=[walls])
            shown_wall = Show(wall, view)
            ColorBy(shown_wall, ("POINTS", None))
            shown_wall.AmbientColor = shown_wall.DiffuseColor = [0.2, 0.2, 0.2]
            shown_wall.LineWidth = 2.0
    shown.RescaleTransferFunctionToDataRange(True, False)
    shown.SetScalarBarVisibility(view, True)
    Render(view)  # the bounds of what is shown, at the last frame
    if three_d:  # an oblique view: from the front, a little from above and the side
        view.CameraFocalPoint = [0.0, 0.0, 0.0]
        view.CameraPosition = [1.0, -2.0, 1.2]
        view.CameraViewUp = [0.0, 0.0, 1.0]
    view.ResetCamera(False)
    Render(view)
    return view


def check_state(state, png, folder):
    """Loads a saved state in a fresh pvbatch (a reset session in the same process keeps the
    earlier states' pipelines), renders it and returns the share of the pixels that differ
    from the background: a state whose wire or shell is missing renders (nearly) background
    only."""
    out = pvbatch("--render", state, png, cwd=folder)
    for line in out.stdout.splitlines():
        if line.startswith("share "):
            return float(line.split()[1])
    raise RuntimeError(f"rendering {state} failed: {out.stdout[-500:]} {out.stderr[-500:]}")


def render_share(state, png):
    LoadState(state)
    view = GetActiveViewOrCreate("RenderView")
    Render(view)
    SaveScreenshot(png, view, ImageResolution=[640, 480], TransparentBackground=0)
    from paraview.vtk.vtkIOImage import vtkPNGReader
    from paraview.vtk.util.numpy_support import vtk_to_numpy
    reader = vtkPNGReader()
    reader.SetFileName(png)
    reader.Update()
    img = reader.GetOutput()
    pix = vtk_to_numpy(img.GetPointData().GetScalars())[:, :3].astype(int)
    background = pix[0]  # a corner
    return float(((abs(pix - background)).sum(axis=1) > 30).mean())


def pvbatch(*args, cwd=None):
    """This script in a fresh pvbatch: a state saved after ResetSession() in the same process
    renders empty when loaded (only the first state of a process was whole), so each state is
    built, and checked, in a process of its own (on the X display of start_display())."""
    return subprocess.run(["pvbatch", os.path.abspath(__file__), *args], capture_output=True,
                          text=True, cwd=cwd, stdin=subprocess.DEVNULL)


def start_display():
    """Without a display, one Xvfb for all the pvbatch processes (xvfb-run per process failed
    at random to open its first window); returns it, to be terminated at the end."""
    if os.environ.get("DISPLAY"):
        return None
    for n in range(90, 140):
        if os.path.exists(f"/tmp/.X11-unix/X{n}") or os.path.exists(f"/tmp/.X{n}-lock"):
            continue
        # -noreset: by default the server resets when a client leaves, and the next pvbatch
        # that connects during the reset cannot open its window
        xvfb = subprocess.Popen(["Xvfb", f":{n}", "-screen", "0", "1280x1024x24", "-nolisten", "tcp",
                                 "-noreset"],
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        for _ in range(100):
            if os.path.exists(f"/tmp/.X11-unix/X{n}"):
                os.environ["DISPLAY"] = f":{n}"
                return xvfb
            if xvfb.poll() is not None:
                break
            time.sleep(0.1)
        xvfb.kill()
    raise RuntimeError("no display and no Xvfb could be started")


def main():
    if sys.argv[1] == "--render":  # one state, one picture
        print("share", render_share(sys.argv[2], sys.argv[3]))
        return
    if sys.argv[1] == "--build":  # one scene's state, in the folder of its files
        scene, deck, variables, trajectory, radius, field = SCENES[int(sys.argv[2])]
        build_view(trajectory, radius, field, three_d=scene != "crumple2d")
        SaveState(sys.argv[3])
        return
    slender = os.path.abspath(sys.argv[1])
    outdir = os.path.abspath(sys.argv[2]) if len(sys.argv) > 2 else None
    check = "--check" in sys.argv[3:]
    if outdir:
        os.makedirs(outdir, exist_ok=True)
    xvfb = start_display()
    try:
        failed = make_states(slender, outdir, check)
    finally:
        if xvfb:
            xvfb.terminate()
    if failed:
        print("states that render (nearly) empty:", ", ".join(failed))
        sys.exit(1)
    if check:
        print("paraview states: ok")


def make_states(slender, outdir, check):
    failed = []
    for k, (scene, deck, variables, trajectory, radius, field) in enumerate(SCENES):
        target = os.path.join(outdir or os.path.join(REPO, "examples", scene), deck + ".pvsm")
        with tempfile.TemporaryDirectory() as tmp:
            run_deck(slender, scene, deck, variables, tmp)
            # the state names the files relative to the folder it is built in
            out = pvbatch("--build", str(k), target, cwd=tmp)
            if out.returncode != 0 or not os.path.exists(target):
                raise RuntimeError(f"building the state of {deck} failed: {out.stderr[-800:]}")
            if check:
                share = check_state(target, os.path.join(outdir or tmp, deck + ".png"), tmp)
                print(f"  {deck}: {100 * share:.1f} % of the picture away from the background")
                if share < 0.02:
                    failed.append(deck)
        print(f"state: {target}")
    return failed


if __name__ == "__main__":
    main()

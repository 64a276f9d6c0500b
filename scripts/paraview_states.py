"""ParaView state files of the flagship scenes (run by ParaView's pvbatch): the wire or rod as
a tube of its own diameter coloured by a per-node field, the cavity walls as lines, the shell
coloured by its bending energy density; with the camera on the whole scene.

  pvbatch scripts/paraview_states.py SLENDER [OUTDIR]

(under xvfb-run where there is no display) runs each scene's fast deck in a temporary folder (the states need the data to set up their
colours), builds the view on the files there and saves examples/<scene>/<deck>.pvsm (or into
OUTDIR). The states name the files relative to the folder ParaView is started in, so open
one where the deck wrote its files, e.g.

  cd out && paraview --state=../examples/crumple2d/classic.pvsm
"""
import os
import subprocess
import sys
import tempfile

from paraview.simple import (ColorBy, ExtractSurface, GetActiveViewOrCreate, GetAnimationScene, Hide,
                             Render, ResetSession, SaveState, Show, Tube, XDMFReader)

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# deck, its -v variables, the trajectory it writes, tube radius (half the wire's diameter or
# the rod's radius), the per-node field to colour by; shells: the surface and a face field
SCENES = [
    ("crumple2d", "classic", {"fast": 1}, "classic.h5", 0.5, "bend.plastic_curvature"),
    # not yet shipped: plastic and spiral (the same view), the 3D packings (their state renders
    # an empty picture so far: to be found) and the e-cone surface (unchecked)
    # ("pack3d", "low_torsion", {"fast": 1}, "low_torsion.h5", 1.0, "bend.energy"),
    # ("shells", "econe", {"fast": 1, "out": "."}, "surface.h5", None, "koiter.Ub"),
]


def run_deck(slender, scene, deck, variables, folder):
    cmd = [slender, "-q", "-log", "none", os.path.join(REPO, "examples", scene, deck + ".lua"),
           "-v", "plots=0"]
    for k, v in variables.items():
        cmd += ["-v", f"{k}={v}"]
    subprocess.run(cmd, cwd=folder, check=True, stdout=subprocess.DEVNULL)


def build_view(trajectory, radius, field):
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
    view.ResetCamera(False)
    Render(view)
    return view


def main():
    slender = os.path.abspath(sys.argv[1])
    outdir = os.path.abspath(sys.argv[2]) if len(sys.argv) > 2 else None
    for scene, deck, variables, trajectory, radius, field in SCENES:
        with tempfile.TemporaryDirectory() as tmp:
            run_deck(slender, scene, deck, variables, tmp)
            cwd = os.getcwd()
            os.chdir(tmp)  # the state names the files relative to this folder
            try:
                build_view(trajectory, radius, field)
                target = os.path.join(outdir or os.path.join(REPO, "examples", scene), deck + ".pvsm")
                SaveState(target)
            finally:
                os.chdir(cwd)
        print(f"state: {target}")


if __name__ == "__main__":
    main()

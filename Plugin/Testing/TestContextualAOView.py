"""The "Render View (Contextual AO)" view in pvpython: CreateView
("ContextualAORenderView") holds ParaView's representations and runs
vtkContextualAOPass between its camera pass and its default pass. A sphere
resting on a box (ParaView sources, drawn by composite mappers):
- the first frames voxelize, cast, trace and combine; against Surface AO
  Method None (the control) the picture only darkens, around the contact,
  not everywhere;
- a colour change runs only the combine; a camera turn casts and traces
  without a new grid; moving the sphere (its source) re-voxelizes;
- the view's properties reach the pass (Strength 0 leaves the picture).
Writes OUT_DIR/view-off.png and view-on.png.

  pvpython TestContextualAOView.py PLUGIN.so OUT_DIR   (under run-with-xvfb.sh)"""
import os
import sys

from paraview.simple import *  # noqa: F401,F403
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.util.numpy_support import vtk_to_numpy

LoadPlugin(sys.argv[1], remote=False, ns=globals())
import contextualao  # noqa: E402,F401  (wraps vtkContextualAOPass)
out = sys.argv[2]
os.makedirs(out, exist_ok=True)
failures = []


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


def shot(name):
    path = os.path.join(out, name + ".png")
    SaveScreenshot(path, view, ImageResolution=[300, 240])
    r = vtkPNGReader()
    r.SetFileName(path)
    r.Update()
    return vtk_to_numpy(r.GetOutput().GetPointData().GetScalars()).astype(float)[:, :3].reshape(240, 300, 3)


view = CreateView("ContextualAORenderView")
view.OrientationAxesVisibility = 0
view.ViewSize = [300, 240]  # the screenshots' size: display coordinates are their pixels
check(view.GetClientSideObject().GetClassName() == "vtkPVRenderViewWithContextualAO",
      "the view is the plugin's (%s)" % view.GetClientSideObject().GetClassName())
box = Box(XLength=4.0, YLength=4.0, ZLength=0.4, Center=[0.0, 0.0, -0.2])
ball = Sphere(Center=[0.0, 0.0, 0.5], Radius=0.5, ThetaResolution=48, PhiResolution=24)
Show(box, view)
ballDisplay = Show(ball, view)
view.CameraPosition = [0.0, -6.0, 4.0]
view.CameraFocalPoint = [0.0, 0.0, 0.2]
view.CameraViewUp = [0.0, 0.0, 1.0]
view.SurfaceAORadius = 0.8
chain = view.GetRenderer().GetPass()
while chain is not None and chain.GetClassName() != "vtkContextualAOPass":
    chain = chain.GetDelegatePass() if hasattr(chain, "GetDelegatePass") else None
check(chain is not None, "the pass is in the view's render pass chain")
pas = chain
on = shot("view-on")
check(pas.GetVoxelizeCount() >= 1 and pas.GetTraceCount() >= 1 and "combine" in pas.GetLastFrameStages(),
      "the view voxelized, traced and combined: %s" % pas.GetLastFrameReport())
view.SurfaceAOMethod = "None"
off = shot("view-off")
check(pas.GetLastFrameStages() == "", "Surface AO Method None runs nothing")
# The AO only darkens, around the contact, and leaves most of the picture.
darker = (off - on).mean(axis=2)
changed = int((darker > 10).sum())
check(darker.min() >= -1 and 300 < changed < 0.5 * darker.size,
      "AO only darkens (largest brightening %.1f), around the contact: %d of %d pixels darker by more "
      "than 10 grey levels" % (-darker.min(), changed, darker.size))
view.SurfaceAOMethod = "Voxel Cones"
Render(view)
grids, traces = pas.GetVoxelizeCount(), pas.GetTraceCount()
ballDisplay.AmbientColor = ballDisplay.DiffuseColor = [0.9, 0.3, 0.2]
Render(view)
check(pas.GetLastFrameStages() == "combine" and pas.GetVoxelizeCount() == grids and pas.GetTraceCount() == traces,
      "a colour change runs only the combine (%s)" % pas.GetLastFrameStages())
view.GetActiveCamera().Azimuth(15)
Render(view)
check(pas.GetLastFrameStages() == "primary,trace,combine" and pas.GetVoxelizeCount() == grids,
      "a camera turn casts and traces without a new grid (%s)" % pas.GetLastFrameStages())
ball.Center = [0.3, 0.0, 0.5]
Render(view)
check(pas.GetVoxelizeCount() == grids + 1 and pas.GetLastFrameStages().startswith("voxelize"),
      "moving the sphere's source re-voxelizes (%s)" % pas.GetLastFrameStages())
view.SurfaceAOStrength = 0.0
a = shot("view-strength0")
view.SurfaceAOMethod = "None"
b = shot("view-none")
check(abs(a - b).max() <= 1, "Strength 0 leaves the picture as Method None (max diff %.0f)" % abs(a - b).max())
print("%d failure(s)" % len(failures))
sys.stdout.flush()
os._exit(1 if failures else 0)

"""Opaque surfaces occluding the volume in vtkContextualAOVolumeMapper
(AddOccluder), judged in the picture: neghip.slc with a ball inside it,
drawn in the project's EGL window.

- The ball makes the volume around it darker (against the same frame with
  no occluder: the volume's pixels that differ are darker on average, and
  none is brighter by more than 2 levels).
- Moving the ball is an opacity edit (the frame report says so, and the
  voxels recomputed are fewer than the volume has), and the frame after the
  move equals, pixel for pixel, a new mapper's frame with the ball already
  there (a full precompute): the edit is exact in the picture.
- Removing the occluder gives the frame of a mapper that never had it
  (the volume back on its 8-bit scalars, the ray caster too).
- An open occluder (a plane) occludes by the voxels its surface passes
  through, without a warning: the volume around it darkens.
- vtkLocalAmbientOcclusion's OpenGL backend with an occluder gives the
  CPU's LAO within half a 16-bit step, with the same voxels opaque.

Negative control, run by hand: with the occluder's change kept out of the
volume key (no edit on a move), the frame after the move differs from the
new mapper's.
"""
import json
import os
import sys

import numpy as np
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkFiltersSources import vtkPlaneSource, vtkSphereSource
from vtkmodules.vtkIOImage import vtkSLCReader
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper

from neghip_scene import add_volume, frame, oblique_camera, window_and_renderer  # (this folder)

data = os.environ.get("CAO_DATA_DIR", "Data")
failures = []


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what, flush=True)
    if not ok:
        failures.append(what)


reader = vtkSLCReader()
reader.SetFileName(os.path.join(data, "neghip.slc"))
reader.Update()


def scene(occluder_source=None, centre=(30, 34, 33), occlude=True):
    window, renderer = window_and_renderer()
    mapper = add_volume(renderer, reader)
    actor = None
    if occluder_source is not None:
        m = vtkPolyDataMapper()
        m.SetInputConnection(occluder_source.GetOutputPort())
        actor = vtkActor()
        actor.SetMapper(m)
        actor.SetPosition(*centre)
        actor.GetProperty().SetColor(0.3, 0.5, 0.9)
        renderer.AddActor(actor)
        if occlude:
            mapper.AddOccluder(actor)
    oblique_camera(renderer)
    return window, renderer, mapper, actor


ball = vtkSphereSource()  # centred at the origin; the actor's position moves it
ball.SetRadius(6)
ball.SetThetaResolution(24)
ball.SetPhiResolution(16)

window, renderer, mapper, actor = scene(ball, (30, 34, 33))
first = frame(window)
report = json.loads(mapper.GetLastFrameReport())
check(any("voxels made opaque by 1 occluder" in r for r in report["reasons"]),
      "the first frame makes the ball's voxels opaque (%s)" % report["reasons"])
actor.SetPosition(32, 36, 33)
moved = frame(window)
report = json.loads(mapper.GetLastFrameReport())
edit = [r for r in report["reasons"] if "opacity changed" in r]
voxels = reader.GetOutput().GetNumberOfPoints()
check(len(edit) == 1 and "within reach recomputed" in edit[0] and
      0 < report["recomputed_voxels"] < voxels,
      "moving the ball is an opacity edit (%s; %d of %d voxels)"
      % (edit, report["recomputed_voxels"], voxels))

fresh_window, _, fresh_mapper, _ = scene(ball, (32, 36, 33))
fresh = frame(fresh_window)
check(np.array_equal(moved, fresh),
      "the frame after the move equals a new mapper's with the ball there (largest difference %d)"
      % np.abs(moved - fresh).max())

# The same scene with the ball drawn but not occluding.
plain_window, _, _, _ = scene(ball, (32, 36, 33), occlude=False)
plain = frame(plain_window)
lum = lambda a: a @ np.array([0.2126, 0.7152, 0.0722])


def check_darkens(occluded, without, what):
    """The occluded frame darker than the one without: over 100 pixels
    differ by more than 2 levels, by over 2 on average, none brighter."""
    differ = np.abs(lum(occluded) - lum(without)) > 2
    darker = float(np.mean(lum(without)[differ] - lum(occluded)[differ])) if differ.any() else 0.0
    brighter = int(np.count_nonzero(lum(occluded) > lum(without) + 2))
    check(differ.sum() > 100 and darker > 2 and brighter == 0,
          "%s darkens the volume around it (%d pixels differ, by %.1f levels on average; %d brighter)"
          % (what, differ.sum(), darker, brighter))


check_darkens(fresh, plain, "the ball")

# Removing the occluder: the volume goes back to its 8-bit scalars on the
# GPU (with the occluder its opacity went up as floats, and the ray caster
# drew its own float copy of the scalars); the frame is a new mapper's
# without an occluder (the ball still drawn), pixel for pixel.
mapper.RemoveAllOccluders()
removed = frame(window)
check(np.array_equal(removed, plain),
      "removing the occluder gives the frame of a mapper that never had it (largest difference %d)"
      % np.abs(removed - plain).max())

# An open occluder (a plane: an isosurface cut by the volume's box, or
# ParaView's tubes, are open too) occludes by the voxels its surface passes
# through: no warning, the report says so, and the volume around it is
# darker than with the plane drawn but not occluding (it was left out with
# a warning before: the control).
warnings = []


@calldata_type(VTK_STRING)
def on_warning(caller, event, text):
    warnings.append(text)


plane = vtkPlaneSource()
plane.SetOrigin(-10, -10, 0)
plane.SetPoint1(10, -10, 0)
plane.SetPoint2(-10, 10, 0)
open_window, _, open_mapper, _ = scene(plane, (32, 36, 33))
open_mapper.AddObserver(vtkCommand.WarningEvent, on_warning)
opened = frame(open_window)
drawn_window, _, _, _ = scene(plane, (32, 36, 33), occlude=False)
text = " ".join(str(w) for w in warnings)
open_report = json.loads(open_mapper.GetLastFrameReport())
check(not text and any("1 open: the voxels their surface passes through" in r for r in open_report["reasons"]),
      "an open occluder occludes by its surface's voxels, without a warning (%s; %s)"
      % (text.strip()[-120:] or "no warning", open_report["reasons"]))
check_darkens(opened, frame(drawn_window), "the open plane")

# The LAO filter's OpenGL backend with an occluder: the CPU's LAO to the
# GPU's 16-bit AO (half a step: 7.6e-6), the same voxels opaque.
from contextualao import vtkLocalAmbientOcclusion  # noqa: E402
placed = vtkSphereSource()
placed.SetCenter(30, 34, 33)
placed.SetRadius(6)
placed.SetThetaResolution(24)
placed.SetPhiResolution(16)
lao_opacity = vtkPiecewiseFunction()
lao_opacity.AddPoint(0, 0.0)
lao_opacity.AddPoint(40, 0.0)
lao_opacity.AddPoint(255, 0.8)
runs = {}
for backend in ("CPU", "OpenGL"):
    f = vtkLocalAmbientOcclusion()
    f.SetInputConnection(reader.GetOutputPort())
    f.SetOpacityFunction(lao_opacity)
    getattr(f, "SetBackendTo" + backend)()
    f.AddOccluderConnection(placed.GetOutputPort())
    f.Update()
    out = f.GetOutput()
    runs[backend] = (vtk_to_numpy(out.GetPointData().GetArray("AmbientOcclusion")).copy(),
                     int(out.GetFieldData().GetArray("LAOOccludedVoxels").GetValue(0)))
gap = float(np.abs(runs["CPU"][0] - runs["OpenGL"][0]).max())
check(runs["CPU"][1] == runs["OpenGL"][1] > 0 and gap <= 0.5 / 65535 + 1e-7,
      "the filter's OpenGL backend with an occluder: %d voxels opaque, AO within %.2g of the CPU's"
      % (runs["OpenGL"][1], gap))

if failures:
    print("%d check(s) failed" % len(failures))
    sys.exit(1)
print("all checks passed")

"""A reader -> LAO -> CAO pipeline (with depth maps on port 1), driven from
/usr/bin/python3: changing the clip pose re-executes only the CAO stage;
changing the opacity transfer function re-executes LAO and CAO but not the
depth maps; a CAO without upstream LAO computes it once and caches it."""
import os
import sys

from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkCommonTransforms import vtkTransform
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkIOImage import vtkSLCReader

from contextualao import (vtkClipDepthMaps, vtkContextualAmbientOcclusion,
                          vtkLocalAmbientOcclusion)

data = os.environ.get("CAO_DATA_DIR", "Data")
runs = {}


def watch(algorithm, name):
    runs[name] = 0

    def started(obj, event):
        runs[name] += 1
    algorithm.AddObserver("StartEvent", started)


def expect(expected, what):
    if runs != expected:
        print(f"FAIL: {what}: executions {runs}, expected {expected}")
        sys.exit(1)
    print(f"ok: {what}: {runs}")


reader = vtkSLCReader()
reader.SetFileName(os.path.join(data, "neghip.slc"))
tf = vtkPiecewiseFunction()
tf.AddPoint(0, 0.0)
tf.AddPoint(40, 0.0)
tf.AddPoint(255, 0.8)
lao = vtkLocalAmbientOcclusion()
lao.SetInputConnection(reader.GetOutputPort())
lao.SetOpacityFunction(tf)
lao.SetQualityToCustom()  # the settings below apply
lao.SetRayPattern(vtkLocalAmbientOcclusion.RAYS_14)
sphere = vtkSphereSource()
sphere.SetRadius(12)
sphere.SetThetaResolution(32)
sphere.SetPhiResolution(32)
maps = vtkClipDepthMaps()
maps.SetInputConnection(sphere.GetOutputPort())
cao = vtkContextualAmbientOcclusion()
cao.SetInputConnection(0, lao.GetOutputPort())
cao.SetInputConnection(1, maps.GetOutputPort())
cao.VerifyOn()
pose = vtkTransform()
cao.SetPoseTransform(pose)
for algorithm, name in ((reader, "reader"), (lao, "lao"), (maps, "maps"), (cao, "cao")):
    watch(algorithm, name)

pose.Translate(20, 30, 33)
cao.Update()
expect({"reader": 1, "lao": 1, "maps": 1, "cao": 1}, "first update")
for step in range(3):
    pose.Translate(4, 1, 0)
    cao.Update()
    diff = cao.GetOutput().GetFieldData().GetArray("Verification").GetComponent(0, 0)
    if diff != 0.0:
        print(f"FAIL: pose {step}: CAO differs from the full recompute by {diff}")
        sys.exit(1)
expect({"reader": 1, "lao": 1, "maps": 1, "cao": 4}, "three pose changes")
cao.Update()
expect({"reader": 1, "lao": 1, "maps": 1, "cao": 4}, "no change, no work")
tf.AddPoint(128, 0.3)
cao.Update()
expect({"reader": 1, "lao": 2, "maps": 1, "cao": 5}, "transfer function edit")
sphere.SetRadius(9)
cao.Update()
expect({"reader": 1, "lao": 2, "maps": 2, "cao": 6}, "clip mesh edit")

# No LAO upstream: CAO computes it once and keeps it across poses.
direct = vtkContextualAmbientOcclusion()
direct.SetInputConnection(0, reader.GetOutputPort())
direct.SetInputConnection(1, maps.GetOutputPort())
direct.SetOpacityFunction(tf)
direct.SetQuality(0)  # Custom: the settings below apply
direct.SetRayPattern(vtkLocalAmbientOcclusion.RAYS_14)
direct.SetPoseTransform(pose)
for step in range(3):
    pose.Translate(-3, 0, 1)
    direct.Update()
if direct.GetPrecomputeCount() != 1:
    print(f"FAIL: the internal LAO ran {direct.GetPrecomputeCount()} times over 3 poses")
    sys.exit(1)
direct.SetReach(5.0)
direct.Update()
if direct.GetPrecomputeCount() != 2:
    print("FAIL: changing the reach must recompute the internal LAO")
    sys.exit(1)
print("ok: internal LAO cached across poses, recomputed when its settings change")

# NaN scalars: the LAO filter warns that they read as transparent once for
# the same scalars; an opacity edit does not repeat it (ParaView re-runs the
# filter at every edit of the map); new scalars warn again (the control).
import numpy as np  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from vtkmodules.util.misc import calldata_type  # noqa: E402
from vtkmodules.vtkCommonCore import VTK_STRING, vtkCommand  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402

nan_image = vtkImageData()
nan_image.SetDimensions(16, 16, 16)
nan_image.AllocateScalars(10, 1)  # float
values = vtk_to_numpy(nan_image.GetPointData().GetScalars())
values[:] = (np.arange(values.size) * 37 % 256).astype(np.float32)
values[:100:10] = np.nan
warnings = []


@calldata_type(VTK_STRING)
def on_warning(obj, event, text):
    warnings.append(text)


nan_lao = vtkLocalAmbientOcclusion()
nan_lao.AddObserver(vtkCommand.WarningEvent, on_warning)
nan_lao.SetInputData(nan_image)
nan_tf = vtkPiecewiseFunction()
nan_tf.AddPoint(0, 0.0)
nan_tf.AddPoint(255, 0.8)
nan_lao.SetOpacityFunction(nan_tf)
nan_lao.Update()
nan_tf.AddPoint(128, 0.3)
nan_lao.Update()
nan_tf.AddPoint(200, 0.1)
nan_lao.Update()
nan_warnings = sum(1 for w in warnings if "NaN or Inf" in w)
print(f"NaN warnings over a run and two opacity edits: {nan_warnings}")
if nan_warnings != 1:
    print(f"FAIL: the NaN warning came {nan_warnings} times for the same scalars (expected once): {warnings}")
    sys.exit(1)
values[5] = np.nan
nan_image.GetPointData().GetScalars().Modified()
nan_lao.Update()
nan_warnings = sum(1 for w in warnings if "NaN or Inf" in w)
if nan_warnings != 2 or "11 NaN or Inf" not in warnings[-1]:
    print(f"FAIL: new scalars with NaN must warn again, with their count: {warnings}")
    sys.exit(1)
# Values changed and only the image marked modified (the array's time
# stays): a new count warns again.
values[6] = np.nan
nan_image.Modified()
nan_lao.Update()
nan_warnings = sum(1 for w in warnings if "NaN or Inf" in w)
if nan_warnings != 3 or "12 NaN or Inf" not in warnings[-1]:
    print(f"FAIL: a new NaN count must warn again: {warnings}")
    sys.exit(1)
print("ok: the NaN warning once per scalars, not per opacity edit; again for new scalars or a new count")

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
lao.SetQualityPresetToCustom()  # the settings below apply
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
direct.SetQualityPreset(0)  # Custom: the settings below apply
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

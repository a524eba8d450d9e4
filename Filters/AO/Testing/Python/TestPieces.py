"""The LAO filter on pieces of a real volume (Data/hydrogen.vti): the output
asked for as a sub-extent, or as piece k of n (as ParaView's parallel
pipelines ask), equals the serial AO of the same voxels bit for bit,
because the filter asks its input for the reach plus the trilinear
footprint around the piece (and no more than the whole extent)."""
import os
import sys

import contextualao as cao
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkIOXML import vtkXMLImageDataReader

data = os.environ["CAO_DATA_DIR"]
failures = []


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


def pipeline():
    reader = vtkXMLImageDataReader()
    reader.SetFileName(os.path.join(data, "hydrogen.vti"))
    tf = vtkPiecewiseFunction()
    tf.AddPoint(0.0, 0.0)
    tf.AddPoint(0.05, 0.1)
    tf.AddPoint(0.4, 0.9)
    lao = cao.vtkLocalAmbientOcclusion()
    lao.SetInputConnection(reader.GetOutputPort())
    lao.SetOpacityFunction(tf)
    lao.SetBackendToCPU()
    return reader, lao, tf


_, serial, _ = pipeline()
serial.Update()
whole = serial.GetOutput()
ref = whole.GetPointData().GetArray("AmbientOcclusion")


def compare(out, what):
    e = out.GetExtent()
    a = out.GetPointData().GetArray("AmbientOcclusion")
    differ = 0
    n = 0
    for k in range(e[4], e[5] + 1):
        for j in range(e[2], e[3] + 1):
            for i in range(e[0], e[1] + 1):
                if a.GetValue(n) != ref.GetValue(i + 64 * (j + 64 * k)):
                    differ += 1
                n += 1
    check(n == a.GetNumberOfTuples() and differ == 0,
          "%s: extent %s, %d voxels, %d differ from serial" % (what, e, n, differ))


spacing = whole.GetSpacing()
GHOST = [int(-(-8.0 * min(spacing) // spacing[d])) + 2 for d in range(3)]  # ceil(reach/h) + 2


def ghosted(e):
    """What the filter must ask its input for: the piece grown by the ghost margin."""
    return tuple(max(0, e[2 * d] - GHOST[d]) if i == 0 else min(63, e[2 * d + 1] + GHOST[d])
                 for d in range(3) for i in (0, 1))


for ext in ((0, 63, 0, 63, 0, 31), (10, 40, 5, 60, 20, 50), (0, 0, 0, 63, 0, 63)):
    reader, lao, tf = pipeline()
    lao.UpdateExtent(ext)
    compare(lao.GetOutput(), "sub-extent")
    got = reader.GetOutput().GetExtent()
    check(got == ghosted(ext), "the input read for %s is %s (expected %s)" % (ext, got, ghosted(ext)))
for piece in range(3):
    reader, lao, tf = pipeline()
    lao.UpdatePiece(piece, 3, 0)
    out = lao.GetOutput()
    compare(out, "piece %d of 3" % piece)
    check(out.GetNumberOfPoints() < 64 ** 3, "piece %d of 3 is a part of the volume (%d voxels)"
          % (piece, out.GetNumberOfPoints()))
    got = reader.GetOutput().GetExtent()
    check(got == ghosted(out.GetExtent()), "piece %d: the input read is %s (expected %s)"
          % (piece, got, ghosted(out.GetExtent())))

# The contextual AO downstream: it asks the LAO for its piece grown by the
# reach (from the LAO's REACH key) plus the trilinear and anti-aliasing
# footprints; the LAO grows that again for itself.
from vtkmodules.vtkFiltersSources import vtkSphereSource  # noqa: E402
from vtkmodules.vtkCommonTransforms import vtkTransform  # noqa: E402


def cao_pipeline():
    reader, lao, tf = pipeline()
    sphere = vtkSphereSource()
    sphere.SetRadius(14.0)
    sphere.SetThetaResolution(32)
    sphere.SetPhiResolution(16)
    maps = cao.vtkClipDepthMaps()
    maps.SetInputConnection(sphere.GetOutputPort())
    maps.SetReach(8.0)
    c = cao.vtkContextualAmbientOcclusion()
    c.SetInputConnection(lao.GetOutputPort())
    c.SetDepthMapsConnection(maps.GetOutputPort())
    pose = vtkTransform()
    pose.Translate(32.0, 30.0, 36.0)
    c.SetPoseTransform(pose)
    c.SetBackendToCPU()
    return reader, lao, c, (tf, sphere, maps, pose)


_, _, serial_cao, keep = cao_pipeline()
serial_cao.Update()
ref = serial_cao.GetOutput().GetPointData().GetArray("AmbientOcclusion")
categories = serial_cao.GetOutput().GetPointData().GetArray("ClipCategory").GetRange()
check(categories == (0.0, 2.0), "the pose clips, affects and leaves voxels")
CAO_GHOST = [g + 1 for g in GHOST]  # one more voxel: the anti-aliasing footprint
for piece in range(3):
    reader, lao, c, keep = cao_pipeline()
    c.UpdatePiece(piece, 3, 0)
    out = c.GetOutput()
    compare(out, "CAO piece %d of 3" % piece)
    e = out.GetExtent()
    expected = tuple(max(0, e[2 * d] - CAO_GHOST[d]) if i == 0 else min(63, e[2 * d + 1] + CAO_GHOST[d])
                     for d in range(3) for i in (0, 1))
    got = lao.GetOutput().GetExtent()
    check(got == expected, "CAO piece %d: the LAO produced %s (expected %s)" % (piece, got, expected))

print("%d failure(s)" % len(failures))
sys.exit(1 if failures else 0)

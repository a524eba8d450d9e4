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

print("%d failure(s)" % len(failures))
sys.exit(1 if failures else 0)

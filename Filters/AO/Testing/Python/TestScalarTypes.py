"""The LAO's opacity and AO do not depend on how the scalars are stored.

A 24^3 ball whose values run from -128 (outside) to 127 (centre), stored as
signed char, short, int, long long, float and double (and, shifted by 128
to 0..255, as unsigned char, unsigned short and unsigned int against the
same shift in float): every integer type must give the opacity and the AO of
the float array bit for bit, through the integer lookup table and the
per-value path alike. The transfer function is transparent below 0, so the
outside (negative values) must be transparent and the AO of an open corner
1.

Before, the integer table was indexed from the range's low end by an
unsigned count added to a signed start: a negative start wrapped to about
1.8e19, so every value of a signed volume with negative values read the
function at its far end (opacity 0.8 for -128: a closed box, AO 0.16-0.47
against the float's 0.16-1). Negative control: this test fails on that
code (every signed type, opacity of -128 read as 0.8)."""
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPiecewiseFunction

from contextualao import vtkLocalAmbientOcclusion as LAO

n = 24
z, y, x = np.mgrid[0:n, 0:n, 0:n]
r = np.sqrt((x - 11.5) ** 2 + (y - 11.5) ** 2 + (z - 11.5) ** 2)
ball = np.clip(127.0 - r * 255.0 / 12.0, -128, 127).round().ravel()

failures = []


def lao_of(values, vtk_type, shift=0.0):
    image = vtkImageData()
    image.SetDimensions(n, n, n)
    array = numpy_to_vtk(values, deep=1, array_type=vtk_type)
    array.SetName("v")
    image.GetPointData().SetScalars(array)
    tf = vtkPiecewiseFunction()
    tf.AddPoint(shift - 128.0, 0.0)
    tf.AddPoint(shift + 0.0, 0.0)
    tf.AddPoint(shift + 127.0, 0.8)
    f = LAO()
    f.SetInputData(image)
    f.SetOpacityFunction(tf)
    f.SetReach(4.0)
    f.SetBackendToCPU()
    f.Update()
    out = f.GetOutput().GetPointData()
    return (vtk_to_numpy(out.GetArray("AmbientOcclusionOpacity")).copy(),
            vtk_to_numpy(out.GetArray("AmbientOcclusion")).copy())


# VTK type ids: 2 char... 15 signed char, 3 unsigned char, 4 short, 5 unsigned
# short, 6 int, 7 unsigned int, 16 long long, 10 float, 11 double.
signed = {"signed char": (15, np.int8), "short": (4, np.int16), "int": (6, np.int32),
          "long long": (16, np.int64), "double": (11, np.float64)}
ref_opacity, ref_ao = lao_of(ball.astype(np.float32), 10)
corner = ref_ao[0]
if not (ref_opacity[0] == 0.0 and corner == 1.0 and ref_ao.min() < 0.9):
    failures.append("float reference: corner opacity %g, corner AO %g, lowest AO %g"
                    % (ref_opacity[0], corner, ref_ao.min()))
for name, (vtk_type, dtype) in signed.items():
    opacity, ao = lao_of(ball.astype(dtype), vtk_type)
    same = np.array_equal(opacity.view(np.uint32), ref_opacity.view(np.uint32)) and \
        np.array_equal(ao.view(np.uint32), ref_ao.view(np.uint32))
    print("%s: %s against float: opacity of -128 %g, AO %.4f..%.4f (float %.4f..%.4f)"
          % ("ok" if same else "FAIL", name, opacity[0], ao.min(), ao.max(), ref_ao.min(), ref_ao.max()))
    if not same:
        failures.append(name)
shifted = ball + 128.0
ref_opacity, ref_ao = lao_of(shifted.astype(np.float32), 10, shift=128.0)
for name, (vtk_type, dtype) in {"unsigned char": (3, np.uint8), "unsigned short": (5, np.uint16),
                                "unsigned int": (7, np.uint32)}.items():
    opacity, ao = lao_of(shifted.astype(dtype), vtk_type, shift=128.0)
    same = np.array_equal(opacity.view(np.uint32), ref_opacity.view(np.uint32)) and \
        np.array_equal(ao.view(np.uint32), ref_ao.view(np.uint32))
    print("%s: %s (0..255) against float" % ("ok" if same else "FAIL", name))
    if not same:
        failures.append(name)
if failures:
    print("FAILED: " + "; ".join(failures))
    sys.exit(1)
print("passed")

"""The grain measure of docs/pictures.md ("Grain") on two frames of the
same view, AO off and AO on: over the pixels whose 5 x 5 neighbourhood is
matter (not the white background) and flat in the AO-off frame (luminance
deviation under 2 of 255), the mean 5 x 5 RMS of the luminance less its
3 x 3 mean, AO on over AO off (AO off's floored at 0.5, an 8-bit frame's
quantisation). The definition of the mapper's test (`calibration` mode),
for frames on `cao render`'s white background (that test's frames are on
black, and it treats the frame's border its own way).

  /usr/bin/python3 grain.py AO_OFF.png AO_ON.png"""
import sys

import numpy
from numpy.lib.stride_tricks import sliding_window_view
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader


def luminance(path):
    r = vtkPNGReader()
    r.SetFileName(path)
    r.Update()
    image = r.GetOutput()
    w, h, _ = image.GetDimensions()
    rgb = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(h, w, -1)[:, :, :3].astype(float)
    return 0.2126 * rgb[:, :, 0] + 0.7152 * rgb[:, :, 1] + 0.0722 * rgb[:, :, 2]


def box(a, r):
    return sliding_window_view(numpy.pad(a, r, mode="edge"), (2 * r + 1, 2 * r + 1)).mean(axis=(2, 3))


def grain(lum):
    return numpy.sqrt(box((lum - box(lum, 1)) ** 2, 2))


off, on = luminance(sys.argv[1]), luminance(sys.argv[2])
matter = box((off < 254.5).astype(float), 2) >= 1.0
deviation = numpy.sqrt(numpy.maximum(box(off ** 2, 2) - box(off, 2) ** 2, 0.0))
mask = matter & (deviation < 2.0)
if not mask.any():
    sys.exit("no flat pixels of matter in " + sys.argv[1])
g_off, g_on = grain(off)[mask].mean(), grain(on)[mask].mean()
print("flat pixels %d  grain AO off %.3f  AO on %.3f  on/off %.2f"
      % (mask.sum(), g_off, g_on, g_on / max(g_off, 0.5)))

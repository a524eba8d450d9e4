"""Side by side: `cao surface --ao-only` pictures (16-bit grey and alpha) over
a dark grey background, written as one 8-bit grey PNG.

    /usr/bin/python3 Rendering/Tool/Benchmark/montage.py [--crop X,Y,W,H] [--zoom N] out.png a.png b.png ...

--crop keeps the W x H pixels from column X, row Y (from the top) of each
picture; --zoom repeats each pixel N x N times (no interpolation).
"""
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter


def tile(path):
    r = vtkPNGReader()
    r.SetFileName(path)
    r.Update()
    image = r.GetOutput()
    w, h, _ = image.GetDimensions()
    a = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(h, w, -1).astype(float)
    full = 65535.0 if a.max() > 255 else 255.0
    grey, alpha = a[..., 0] / full, a[..., -1] / full
    return (41.0 / 255.0) * (1.0 - alpha) + grey * alpha


args = sys.argv[1:]
crop, zoom = None, 1
while args and args[0] in ("--crop", "--zoom") and len(args) > 1:
    try:
        if args[0] == "--crop":
            crop = [int(v) for v in args[1].split(",")]
            if len(crop) != 4 or min(crop) < 0 or crop[2] < 1 or crop[3] < 1:
                raise ValueError
        else:
            zoom = int(args[1])
            if not 1 <= zoom <= 16:
                raise ValueError
    except ValueError:
        sys.exit("--crop takes X,Y,W,H (four whole numbers, W and H at least 1); --zoom a whole number from 1 to 16;"
                 " got %s %s" % (args[0], args[1]))
    args = args[2:]
if len(args) < 2:
    sys.exit(__doc__)


def part(path):
    t = tile(path)[::-1]  # rows from the top
    if crop:
        x, y, w, h = crop
        if y + h > t.shape[0] or x + w > t.shape[1]:
            sys.exit("--crop %s lies outside %s (%d x %d)" % (crop, path, t.shape[1], t.shape[0]))
        t = t[y:y + h, x:x + w]
    return np.kron(t, np.ones((zoom, zoom)))[::-1]


row = np.concatenate([part(p) for p in args[1:]], axis=1)
h, w = row.shape
out = vtkImageData()
out.SetDimensions(w, h, 1)
out.GetPointData().SetScalars(numpy_to_vtk(np.clip(row * 255.0 + 0.5, 0, 255).astype(np.uint8).ravel(),
                                           deep=True))
writer = vtkPNGWriter()
writer.SetFileName(args[0])
writer.SetInputData(out)
writer.Write()

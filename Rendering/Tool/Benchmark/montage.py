"""Side by side: `cao surface --ao-only` pictures (16-bit grey and alpha) over
a dark grey background, written as one 8-bit grey PNG.

    /usr/bin/python3 Rendering/Tool/Benchmark/montage.py out.png a.png b.png ...
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


if len(sys.argv) < 3:
    sys.exit(__doc__)
row = np.concatenate([tile(p) for p in sys.argv[2:]], axis=1)
h, w = row.shape
out = vtkImageData()
out.SetDimensions(w, h, 1)
out.GetPointData().SetScalars(numpy_to_vtk(np.clip(row * 255.0 + 0.5, 0, 255).astype(np.uint8).ravel(),
                                           deep=True))
writer = vtkPNGWriter()
writer.SetFileName(sys.argv[1])
writer.SetInputData(out)
writer.Write()

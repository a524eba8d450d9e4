"""What the representation tests that compare pictures share: the phantom
(a 48^3 ball, 255 at its centre falling by 10 a voxel, with a tunnel
8 x 8 voxels across along y), a screenshot read back as RGB, and the share
of pixels apart.

  sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
  import volume_phantom"""
import numpy
from paraview.simple import SaveScreenshot
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

N = 48


def ball_with_tunnel():
    """The phantom's N^3 values (uint8, x fastest)."""
    z, y, x = numpy.mgrid[0:N, 0:N, 0:N]
    ball = numpy.clip(255 - 10 * numpy.sqrt((x - 24.0) ** 2 + (y - 24.0) ** 2 + (z - 24.0) ** 2),
                      0, 255)
    ball[20:28, :, 20:28] = 0
    return ball.astype(numpy.uint8).ravel()


def picture(view, path, size=200):
    """The view saved to `path` at size x size, read back as float RGB rows."""
    SaveScreenshot(path, view, ImageResolution=[size, size])
    r = vtkPNGReader()
    r.SetFileName(path)
    r.Update()
    return vtk_to_numpy(r.GetOutput().GetPointData().GetScalars()).astype(float)[:, :3]


def apart(a, b, shift=0):
    """The share of pixels whose colour differs by more than 2 levels from
    b's at the same pixel, or, with `shift`, from every pixel of b within
    `shift` pixels (a picture moved by less than a pixel)."""
    side = int(round(len(a) ** 0.5))
    a = a.reshape(side, side, 3)
    b = b.reshape(side, side, 3)
    near = numpy.zeros((side, side), dtype=bool)
    for dy in range(-shift, shift + 1):
        for dx in range(-shift, shift + 1):
            moved = numpy.roll(numpy.roll(b, dy, axis=0), dx, axis=1)
            near |= numpy.abs(a - moved).max(axis=2) <= 2.0
    return float((~near).mean())


def covered(a):
    """The share of pixels that differ from the corner's (the background)."""
    return float((numpy.abs(a - a[0]).max(axis=1) > 10).mean())

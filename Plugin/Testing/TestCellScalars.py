"""The "Contextual AO Volume" representation draws an image's cell scalars:
each cell as a voxel at its centre, as ParaView's own Volume does.

A 48^3 phantom (a ball with a tunnel) as the cell data of a 49^3-point
image at origin 0, and the same values as the point data of a 48^3 image
at origin 0.5 (the cells' centres): with the same camera, the AO on and a
Clip Shape Sphere off and on, the two pictures must be the same within 2
levels of 255 at all but 0.1% of the pixels. Before, the cell data was
refused ("cell scalars are not supported") and nothing was drawn.

The same with spacing (1, 1.5, 0.75), an extent from (3, -2, 5) and the
axes turned by 30 degrees (the centres written out by hand).

The negative control: the point image at origin 0 (the values half a voxel
off the cells' centres) differs from the cell picture at more than 0.5%
of the pixels, so the comparison sees a half-voxel shift. A one-cell-thick
image is refused with the reason (2 cells, 3 points, along each axis). An image
with no arrays, or coloured by Solid Color, draws nothing and says so once.

  pvpython TestCellScalars.py PLUGIN.so OUT_DIR   (under Testing/run-with-xvfb.sh)"""
import os
import sys

import numpy
from paraview.simple import *  # noqa: F401,F403
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow
from vtkmodules.vtkCommonDataModel import vtkImageData

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from volume_phantom import N as n, apart, ball_with_tunnel, covered  # noqa: E402
import volume_phantom  # noqa: E402

LoadPlugin(sys.argv[1], remote=False, ns=globals())
out = sys.argv[2]
os.makedirs(out, exist_ok=True)
values = ball_with_tunnel()


def producer(points, origin, cells=False, dims=None, spacing=(1.0, 1.0, 1.0), start=(0, 0, 0),
             direction=None, name="v"):
    image = vtkImageData()
    d = dims or ((n + 1,) * 3 if cells else (n,) * 3)
    image.SetExtent(start[0], start[0] + d[0] - 1, start[1], start[1] + d[1] - 1,
                    start[2], start[2] + d[2] - 1)
    image.SetOrigin(origin)
    image.SetSpacing(spacing)
    if direction is not None:
        image.SetDirectionMatrix(*direction)
    array = numpy_to_vtk(points, deep=1)
    array.SetName(name)
    data = image.GetCellData() if cells else image.GetPointData()
    data.SetScalars(array)
    p = TrivialProducer()
    p.GetClientSideObject().SetOutput(image)
    p.UpdatePipeline()
    return p


view = CreateView("RenderView")
view.OrientationAxesVisibility = 0
view.CameraPosition = [24.0 + 90.0, 24.0 - 60.0, 24.0 + 70.0]
view.CameraFocalPoint = [24.0, 24.0, 24.0]
view.CameraViewUp = [0.0, 0.0, 1.0]
view.CameraViewAngle = 30.0


def picture(source, association, clip, name):
    display = Show(source, view)
    ColorBy(display, (association, "v"))
    GetColorTransferFunction("v").RescaleTransferFunction(0.0, 255.0)
    GetOpacityTransferFunction("v").RescaleTransferFunction(0.0, 255.0)
    display.SetRepresentationType("Contextual AO Volume")
    display.ClipShape = clip
    if clip == "Sphere":
        display.ClipPosition = [24.0, 24.0, 48.0]
        display.ClipScale = [16.0, 16.0, 16.0]
    shot = volume_phantom.picture(view, os.path.join(out, name + ".png"))
    Hide(source, view)
    return shot


cells = producer(values, (0.0, 0.0, 0.0), cells=True)
centres = producer(values, (0.5, 0.5, 0.5))
corners = producer(values, (0.0, 0.0, 0.0))
failures = []
for clip in ("None", "Sphere"):
    a = picture(cells, "CELLS", clip, "cells-clip-" + clip.lower())
    b = picture(centres, "POINTS", clip, "points-at-centres-clip-" + clip.lower())
    share = apart(a, b)
    drawn = covered(a)
    ok = share <= 0.001 and drawn > 0.05
    print("%s: clip %s: cell scalars against the same values at the cells' centres: %.3f%% of "
          "the pixels apart (at most 0.1%%); the volume covers %.1f%% of the picture"
          % ("ok" if ok else "FAIL", clip, 100 * share, 100 * drawn))
    if not ok:
        failures.append("clip %s: %.3f%% apart, %.1f%% drawn" % (clip, 100 * share, 100 * drawn))
    if clip == "None":
        c = picture(corners, "POINTS", clip, "points-at-corners")
        share = apart(a, c)
        ok = share > 0.005
        print("%s: negative control: the values half a voxel off (origin 0): %.1f%% of the "
              "pixels apart" % ("ok" if ok else "FAIL", 100 * share))
        if not ok:
            failures.append("negative control: a half-voxel shift was not seen")

# A non-trivial geometry: spacing (1, 1.5, 0.75), an extent starting at
# (3, -2, 5), the axes turned by 30 degrees about z; the cells' centres
# written out by hand: origin + R (spacing * (index + 0.5)).
c, s30 = numpy.cos(numpy.radians(30.0)), numpy.sin(numpy.radians(30.0))
R = numpy.array([[c, -s30, 0.0], [s30, c, 0.0], [0.0, 0.0, 1.0]])
spacing = numpy.array([1.0, 1.5, 0.75])
start = (3, -2, 5)
origin = numpy.array([-40.0, 10.0, -2.0])
centre0 = origin + R.dot(spacing * (numpy.array(start) + 0.5)) - R.dot(spacing * numpy.array(start))
turned_cells = producer(values, tuple(origin), cells=True, spacing=tuple(spacing), start=start,
                        direction=tuple(R.ravel()))
turned_points = producer(values, tuple(centre0), spacing=tuple(spacing), start=start,
                         direction=tuple(R.ravel()))
middle = origin + R.dot(spacing * (numpy.array(start) + n / 2.0))
view.CameraFocalPoint = list(middle)
view.CameraPosition = list(middle + numpy.array([90.0, -60.0, 70.0]))
a = picture(turned_cells, "CELLS", "None", "turned-cells")
b = picture(turned_points, "POINTS", "None", "turned-points-at-centres")
share = apart(a, b)
drawn = covered(a)
ok = share <= 0.001 and drawn > 0.05
print("%s: spacing (1, 1.5, 0.75), extent from (3, -2, 5), turned 30 degrees: %.3f%% of the "
      "pixels apart (at most 0.1%%); the volume covers %.1f%%" % ("ok" if ok else "FAIL", 100 * share,
                                                                100 * drawn))
if not ok:
    failures.append("turned geometry: %.3f%% apart, %.1f%% drawn" % (100 * share, 100 * drawn))

# One cell thick along z: refused with the reason.
log = vtkStringOutputWindow()
vtkOutputWindow.SetInstance(log)
thin = producer(values[: n * n], (0.0, 0.0, 0.0), cells=True, dims=(n + 1, n + 1, 2))
picture(thin, "CELLS", "None", "one-cell-thick")
vtkOutputWindow.SetInstance(None)
text = log.GetOutput()
ok = "2 cells, 3 points" in text
print("%s: a one-cell-thick image is refused with the reason: %s"
      % ("ok" if ok else "FAIL", " ".join(text.split())[-160:]))
if not ok:
    failures.append("the one-cell-thick image was not refused with its reason")

# No array to draw: an image with no point or cell arrays, and one coloured
# by Solid Color, draw nothing and say why, once (three renders, one
# warning each). Control: coloured by its array, the same image draws, and
# no warning comes.
bare = vtkImageData()
bare.SetDimensions(n, n, n)
bare_source = TrivialProducer()
bare_source.GetClientSideObject().SetOutput(bare)
bare_source.UpdatePipeline()
for case, source, colour in (("no arrays", bare_source, None), ("Solid Color", centres, None),
                             ("coloured by v (control)", centres, ("POINTS", "v"))):
    log = vtkStringOutputWindow()
    vtkOutputWindow.SetInstance(log)
    display = Show(source, view)
    display.SetRepresentationType("Contextual AO Volume")
    ColorBy(display, colour)
    shots = [volume_phantom.picture(view, os.path.join(out, "bare-%d.png" % i)) for i in range(3)]
    Hide(source, view)
    vtkOutputWindow.SetInstance(None)
    text = " ".join(log.GetOutput().split())
    said = text.count("Contextual AO Volume draws nothing")
    drawn = covered(shots[-1])
    if colour is None:
        words = "no point or cell arrays" if source is bare_source else "Solid Color"
        ok = said == 1 and words in text and drawn < 0.001
    else:
        ok = said == 0 and drawn > 0.05
    print("%s: %s: %d warning(s) over three renders, %.1f%% drawn: %s"
          % ("ok" if ok else "FAIL", case, said, 100 * drawn, text[-200:]))
    if not ok:
        failures.append("%s: %d warnings, %.1f%% drawn" % (case, said, 100 * drawn))

if failures:
    print("FAILED: " + "; ".join(failures))
    sys.exit(1)
print("passed")

"""The pictures issue's block phantom in ParaView's "Contextual AO Volume"
representation at its defaults: open faces keep their light and the slot
darkens, in the rendered frame (what the user sees), as the mapper's own
test (TestContextualAOVolumeMapper calibration) and `cao render` find.

The phantom: 64^3, a solid block 48 x 48 x 32 (value 255) on the volume's
floor (value 0 around it), with a slot 4 voxels wide and 16 deep along y.
ParaView's default maps for the array except the colours, a grey ramp so
that luminance reads the light (the default Cool to Warm puts the block at
about 40 of 255, where one level is 2.5%). Pictures at 256 x 256; the
ratio is the luminance with AO on over AO off.

- Top view, parallel projection, Shade off (ParaView's default: ambient
  only) and on: the open face (6 or more voxels from every edge and from
  the slot) at >= 0.95; the slot's floor seen through it, ambient only,
  at <= 0.70 (the issue's targets).
- Four oblique views (elevation 45, azimuths 30, 120, 210, 300), Shade
  off and on: the median over the block's pixels >= 0.95.
- Negative control: AO Calibration "None (raw LAO)" fails the open face's
  bounds ambient only, top and oblique (it is the LAO of the voxels behind
  the face: about a quarter), so the measures see a dark face.

  pvpython TestPhantomInPicture.py PLUGIN.so OUT_DIR   (under Testing/run-with-xvfb.sh)"""
import os
import sys

import numpy
from paraview.simple import *  # noqa: F401,F403
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonDataModel import vtkImageData

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import volume_phantom  # noqa: E402

LoadPlugin(sys.argv[1], remote=False, ns=globals())
out = sys.argv[2]
os.makedirs(out, exist_ok=True)

N, SIZE = 64, 256
PIXELS_PER_VOXEL = SIZE / float(N)
values = numpy.zeros((N, N, N), dtype=numpy.uint8)  # z, y, x
values[0:32, 8:56, 8:56] = 255
values[16:32, 8:56, 30:34] = 0
image = vtkImageData()
image.SetDimensions(N, N, N)
array = numpy_to_vtk(values.ravel(), deep=1)
array.SetName("s")
image.GetPointData().SetScalars(array)
producer = TrivialProducer()
producer.GetClientSideObject().SetOutput(image)
producer.UpdatePipeline()

view = CreateView("RenderView")
view.OrientationAxesVisibility = 0
display = Show(producer, view)
ColorBy(display, ("POINTS", "s"))
GetColorTransferFunction("s").ApplyPreset("Grayscale", True)
display.SetRepresentationType("Contextual AO Volume")


def luminance(name):
    rgb = volume_phantom.picture(view, os.path.join(out, name + ".png"), SIZE)
    return (0.2126 * rgb[:, 0] + 0.7152 * rgb[:, 1] + 0.0722 * rgb[:, 2]).reshape(SIZE, SIZE)


def top_view():
    view.CameraParallelProjection = 1
    view.CameraFocalPoint = [31.5, 31.5, 0.0]
    view.CameraPosition = [31.5, 31.5, 300.0]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.CameraParallelScale = N / 2.0


def oblique_view(azimuth):
    view.CameraParallelProjection = 0
    ResetCamera(view)
    camera = GetActiveCamera()
    camera.SetFocalPoint(31.5, 31.5, 16.0)
    camera.SetPosition(31.5, -150.0, 16.0)
    camera.SetViewUp(0.0, 0.0, 1.0)
    camera.Azimuth(azimuth)
    camera.Elevation(45.0)
    ResetCamera(view)


def region(x0, x1, y0, y1):
    """Rows and columns of the top view's pixels whose centres lie over
    world x in [x0, x1], y in [y0, y1] (rows from the bottom, as VTK reads
    a PNG)."""
    centre = (numpy.arange(SIZE) + 0.5 - SIZE / 2.0) / PIXELS_PER_VOXEL + 31.5
    cols = numpy.nonzero((centre >= x0) & (centre <= x1))[0]
    rows = numpy.nonzero((centre >= y0) & (centre <= y1))[0]
    return numpy.ix_(rows, cols)


OPEN_FACE = region(14.0, 24.0, 14.0, 49.0)   # 6+ voxels from the block's edges and the slot
SLOT_FLOOR = region(31.0, 32.0, 14.0, 49.0)  # the slot (points 30-33 are 0) seen from above

failures = []


def check(ok, text):
    print("%s: %s" % ("ok" if ok else "FAIL", text))
    if not ok:
        failures.append(text)


def frames(name):
    display.AmbientOcclusion = 1
    on = luminance(name + "-ao-on")
    display.AmbientOcclusion = 0
    off = luminance(name + "-ao-off")
    display.AmbientOcclusion = 1
    return on, off


def top_ratios(name):
    top_view()
    on, off = frames(name)
    face = on[OPEN_FACE].mean() / off[OPEN_FACE].mean()
    slot = on[SLOT_FLOOR].mean() / off[SLOT_FLOOR].mean()
    return face, slot, off


for shade in (0, 1):
    display.Shade = shade
    kind = "shaded" if shade else "ambient only"
    face, slot, off = top_ratios("top-shade%d" % shade)
    check(off[OPEN_FACE].mean() > 100,
          "top view, %s: the open face is drawn, AO off (mean luminance %.0f of 255)"
          % (kind, off[OPEN_FACE].mean()))
    check(face >= 0.95, "top view, %s: open face AO on / AO off %.3f (at least 0.95)" % (kind, face))
    if not shade:
        check(slot <= 0.70, "top view, ambient only: slot floor AO on / AO off %.3f (at most 0.70)" % slot)
    for azimuth in (30, 120, 210, 300):
        oblique_view(azimuth)
        on, off = frames("oblique-%d-shade%d" % (azimuth, shade))
        block = numpy.abs(off - off[0, 0]) > 8.0
        median = float(numpy.median(on[block] / numpy.maximum(off[block], 1.0)))
        check(block.sum() > 2000 and median >= 0.95,
              "azimuth %d, elevation 45, %s: median over the block's %d pixels AO on / AO off %.3f "
              "(at least 0.95)" % (azimuth, kind, block.sum(), median))

# Negative control: the raw LAO darkens the open face.
display.Shade = 0
display.AOCalibration = 0
face, slot, off = top_ratios("top-raw-lao")
check(face < 0.95, "negative control: the raw LAO's open face %.3f fails the 0.95 bound" % face)
oblique_view(30)
on, off = frames("oblique-raw-lao")
block = numpy.abs(off - off[0, 0]) > 8.0
median = float(numpy.median(on[block] / numpy.maximum(off[block], 1.0)))
check(median < 0.95, "negative control: the raw LAO's oblique median %.3f fails the 0.95 bound" % median)
display.AOCalibration = 1

if failures:
    print("FAILED: " + "; ".join(failures))
    sys.exit(1)
print("passed")

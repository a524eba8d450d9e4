"""The "Contextual AO Volume" representation draws a volume far from the
origin or micrometres across as it draws it at home, clipped and not.

One phantom (a 48^3 ball with a tunnel) at home (origin 0, spacing 1), at
origin 1e10, at origin (1e15, -1e15, 1e15), and at spacing 1e-12; AO on,
ParaView's default maps, the camera reset to it; unclipped, and cut by a
Clip Shape Sphere of a third of its width centred on its top face. Each
picture must equal the one at home within 2 levels of 255 at all but 0.5%
of the pixels (at 1e15, 3% within a pixel's move: ParaView's camera, in
double, is placed to 0.125 there), and the cut one must differ from the uncut one (the clip
carves at every placement).

What failed before: at 1e10 the ray caster's float world coordinates
(1e10 +- 1e3) drew a flat box and the clip did not carve; at 1e15 nothing
was drawn; at spacing 1e-12 the clip's scale was floored at 1e-9, so the
sphere covered the whole volume and it vanished. The negative control:
ParaView's own Volume representation at 1e10 draws nothing (ParaView 5.11),
and the same comparison reports it.

  pvpython TestFarAndTiny.py PLUGIN.so OUT_DIR   (under Testing/run-with-xvfb.sh)"""
import os
import sys

from paraview.simple import *  # noqa: F401,F403
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonDataModel import vtkImageData

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from volume_phantom import N as n, apart, ball_with_tunnel  # noqa: E402
import volume_phantom  # noqa: E402

LoadPlugin(sys.argv[1], remote=False, ns=globals())
out = sys.argv[2]
os.makedirs(out, exist_ok=True)
scalars = ball_with_tunnel()

PLACEMENTS = [
    ("home", (0.0, 0.0, 0.0), 1.0),
    ("origin-1e10", (1e10, 1e10, 1e10), 1.0),
    ("origin-1e15", (1e15, -1e15, 1e15), 1.0),
    ("spacing-1e-12", (0.0, 0.0, 0.0), 1e-12),
]


def source(origin, spacing):
    image = vtkImageData()
    image.SetDimensions(n, n, n)
    image.SetOrigin(origin)
    image.SetSpacing(spacing, spacing, spacing)
    array = numpy_to_vtk(scalars, deep=1)
    array.SetName("s")
    image.GetPointData().SetScalars(array)
    producer = TrivialProducer()
    producer.GetClientSideObject().SetOutput(image)
    producer.UpdatePipeline()
    return producer


def picture(view, name):
    return volume_phantom.picture(view, os.path.join(out, name + ".png"))


failures = []
home = {}
for name, origin, spacing in PLACEMENTS:
    producer = source(origin, spacing)
    view = CreateView("RenderView")
    view.OrientationAxesVisibility = 0
    display = Show(producer, view)
    ColorBy(display, ("POINTS", "s"))
    bounds = producer.GetDataInformation().GetBounds()
    pictures = {}
    if name in ("home", "origin-1e10"):
        display.SetRepresentationType("Volume")
        ResetCamera(view)
        pictures["ParaView Volume"] = picture(view, name + "-paraview-volume")
    display.SetRepresentationType("Contextual AO Volume")
    ResetCamera(view)
    for clip in ("None", "Sphere"):
        display.ClipShape = clip
        if clip == "Sphere":
            radius = (bounds[1] - bounds[0]) / 3.0
            display.ClipPosition = [0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]),
                                    bounds[5]]
            display.ClipScale = [radius, radius, radius]
        pictures[clip] = picture(view, "%s-clip-%s" % (name, clip.lower()))
    Delete(view)
    carved = apart(pictures["None"], pictures["Sphere"])
    ok = carved > 0.02
    print("%s: %s: the clip changes %.1f%% of the pixels (more than 2%%)"
          % ("ok" if ok else "FAIL", name, 100 * carved))
    if not ok:
        failures.append(name + ": the clip did not carve")
    if name == "home":
        home = pictures
        continue
    # At 1e15 a double's step is 0.125: ParaView's camera there (in double)
    # sits up to that far from where it would be at home, half a pixel of
    # this phantom at 200 x 200, so the picture may move by a pixel, and
    # every ray's samples move against the voxels by up to a quarter of the
    # sample distance (measured: 1.4-1.5% of the pixels more than 2 levels
    # from every pixel within one; a lost or flat volume is 29%).
    shift, bound = (1, 0.03) if name == "origin-1e15" else (0, 0.005)
    for key in ("None", "Sphere"):
        share = apart(pictures[key], home[key], shift)
        ok = share <= bound
        print("%s: %s, clip %s: %.2f%% of the pixels differ from home's by more than 2 levels "
              "(within %d pixel; at most %.1f%%)" % ("ok" if ok else "FAIL", name, key, 100 * share, shift,
                                        100 * bound))
        if not ok:
            failures.append("%s clip %s: %.2f%% apart" % (name, key, 100 * share))
    if "ParaView Volume" in pictures:
        share = apart(pictures["ParaView Volume"], home["ParaView Volume"])
        ok = share > 0.005
        print("%s: negative control: ParaView's own Volume at %s: %.1f%% of the pixels differ "
              "from its picture at home (the comparison sees a volume lost to precision)"
              % ("ok" if ok else "FAIL", name, 100 * share))
        if not ok:
            failures.append("negative control: ParaView's Volume at %s matched home" % name)

if failures:
    print("FAILED: " + "; ".join(failures))
    sys.exit(1)
print("passed")

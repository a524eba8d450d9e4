"""What a frame costs in ParaView: the "Contextual AO Volume" representation
against ParaView's own Volume representation, side by side in one pvpython
run, same view, volume and colour map.

  pvpython frame_cost.py --plugin ContextualAO.so VOLUME [--size 800x600] [--frames 10]

Rows: ParaView's Volume (Shade on, and off); ours with AO off; ours with AO
on while the camera turns 2 degrees a frame; ours with AO on while the clip
sphere moves (the camera still); then the interactive frames ParaView
draws while the user drags or turns (the view's InteractiveRender: the
render window asks for 5 frames a second, so both mappers lower their
resolution): ParaView's shaded Volume turning, ours turning and ours with
the clip moving. Each row renders one warm-up frame (the first frame
precomputes; an interactive row also one interactive frame), then
--frames frames, and prints the median
milliseconds per frame and its ratio to ParaView's shaded Volume. No
assertion: a table to read (docs/ has measured ones, with the machine)."""
import argparse
import statistics
import sys
import time

from paraview.simple import *  # noqa: F401,F403

parser = argparse.ArgumentParser()
parser.add_argument("volume")
parser.add_argument("--plugin", required=True)
parser.add_argument("--size", default="800x600")
parser.add_argument("--frames", type=int, default=10)
args = parser.parse_args()
width, height = (int(v) for v in args.size.split("x"))
LoadPlugin(args.plugin, remote=False, ns=globals())
try:
    import contextualao  # noqa: E402,F401  (the mapper's report)
except ImportError:
    # The wrapped package of the same build: python/ next to lib/ (a build
    # tree, lib/paraview-5.11/plugins/ContextualAO/, or an install).
    import os
    root = os.path.abspath(os.path.join(os.path.dirname(args.plugin), *[os.pardir] * 4))
    sys.path.insert(0, os.path.join(root, "python"))
    try:
        import contextualao  # noqa: E402,F401
    except ImportError:
        sys.exit("frame_cost.py: the contextualao package is neither on PYTHONPATH nor in %s"
                 % os.path.join(root, "python"))

reader = OpenDataFile(args.volume)
reader.UpdatePipeline()
info = reader.GetDataInformation()
bounds = info.GetBounds()
array = reader.PointData.keys()[0]
lo, hi = reader.PointData[array].GetRange()
centre = [0.5 * (bounds[2 * d] + bounds[2 * d + 1]) for d in range(3)]
extent = max(bounds[2 * d + 1] - bounds[2 * d] for d in range(3))
view = CreateView("RenderView")
view.ViewSize = [width, height]
view.OrientationAxesVisibility = 0
lut = GetColorTransferFunction(array)
lut.ApplyPreset("Cool to Warm", True)
lut.RescaleTransferFunction(lo, hi)
pwf = GetOpacityTransferFunction(array)
pwf.Points = [lo, 0.0, 0.5, 0.0, lo + 0.25 * (hi - lo), 0.0, 0.5, 0.0, hi, 0.8, 0.5, 0.0]
display = Show(reader, view)
ColorBy(display, ("POINTS", array))
display.Shade = 1


def frames(setup, step, interactive=False):
    setup()
    view.ResetCamera()
    Render(view)  # warm-up: the first frame precomputes
    if interactive:
        view.SMProxy.InteractiveRender()  # and the first interactive frame
    times = []
    for k in range(args.frames):
        step(k)
        start = time.perf_counter()
        if interactive:
            view.SMProxy.InteractiveRender()  # as ParaView renders while the user drags
        else:
            Render(view)
        times.append(1000.0 * (time.perf_counter() - start))
    return statistics.median(times), min(times), max(times)


def camera(k):
    view.GetActiveCamera().Azimuth(2.0)


def clip(k):
    p = list(display.ClipPosition)
    p[0] = centre[0] + 0.15 * extent * ((k % 6) - 2.5) / 2.5
    display.ClipPosition = p


def paraview_volume(shade):
    def setup():
        display.SetRepresentationType("Volume")
        display.Shade = shade
    return setup


def ours(ao):
    def setup():
        display.SetRepresentationType("Contextual AO Volume")
        display.Shade = 1
        display.ClipShape = "Sphere"
        display.AmbientOcclusion = ao
    return setup


rows = [("ParaView Volume, Shade on", paraview_volume(1), camera, False),
        ("ParaView Volume, Shade off", paraview_volume(0), camera, False),
        ("ours, AO off, camera turning", ours(0), camera, False),
        ("ours, AO on, camera turning", ours(1), camera, False),
        ("ours, AO on, clip moving", ours(1), clip, False),
        ("ParaView Volume, Shade on, interactive, camera turning", paraview_volume(1), camera, True),
        ("ours, AO on, interactive, camera turning", ours(1), camera, True),
        ("ours, AO on, interactive, clip moving", ours(1), clip, True)]
results = []
for name, setup, step, interactive in rows:
    results.append((name,) + frames(setup, step, interactive))
base = results[0][1]
print("%s, %dx%d, %d frames a row (median, min-max ms)" % (args.volume, width, height, args.frames))
print("| renderer | ms per frame | min-max | x ParaView Volume, shaded |")
print("|---|---:|---:|---:|")
for name, median, low, high in results:
    print("| %s | %.0f | %.0f-%.0f | %.2f |" % (name, median, low, high, median / base))
mapper = display.GetClientSideObject().GetActiveRepresentation().GetActor().GetMapper()
if hasattr(mapper, "GetLastFrameReport"):
    print("last frame report: %s" % mapper.GetLastFrameReport())
sys.stdout.flush()

"""The clip pose animates as any ParaView property does: a keyframe track
on the representation's Clip Position (the mechanism the GUI's Animation
View creates, vtkSMPropertyAnimationCue) moves the clip sphere across
HeadMR; SaveAnimation writes one frame per time step; the property takes the
interpolated value at each time, and the frames differ. Negative control: a
track whose two keyframes hold the same value gives identical frames (the
difference seen is the animation, not noise).

  pvpython TestPoseAnimation.py PLUGIN.so OUTPUT_DIR   (under run-with-xvfb.sh)"""
import os
import sys

from paraview.simple import *  # noqa: F401,F403
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.util.numpy_support import vtk_to_numpy

LoadPlugin(sys.argv[1], remote=False, ns=globals())
out = sys.argv[2]
os.makedirs(out, exist_ok=True)
failures = []


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


def pixels(path):
    r = vtkPNGReader()
    r.SetFileName(path)
    r.Update()
    return vtk_to_numpy(r.GetOutput().GetPointData().GetScalars()).astype(int)


reader = OpenDataFile(os.path.join(os.environ["CAO_DATA_DIR"], "HeadMRVolume.mhd"))
view = CreateView("RenderView")
view.OrientationAxesVisibility = 0
display = Show(reader, view)
ColorBy(display, ("POINTS", "MetaImage"))
display.SetRepresentationType("Contextual AO Volume")
opacity = GetOpacityTransferFunction("MetaImage")
opacity.Points = [0.0, 0.0, 0.5, 0.0, 40.0, 0.0, 0.5, 0.0, 90.0, 0.4, 0.5, 0.0, 255.0, 0.9, 0.5, 0.0]
display.ClipShape = "Sphere"
display.ClipScale = [50.0, 50.0, 50.0]
view.ResetCamera()
scene = GetAnimationScene()
scene.PlayMode = "Sequence"
scene.NumberOfFrames = 3
scene.StartTime = 0.0
scene.EndTime = 1.0


def animate(name, x0, x1):
    track = GetAnimationTrack("ClipPosition", index=0, proxy=display)
    track.KeyFrames = [CompositeKeyFrame(KeyTime=0.0, KeyValues=[x0]),
                       CompositeKeyFrame(KeyTime=1.0, KeyValues=[x1])]
    path = os.path.join(out, name + ".png")
    SaveAnimation(path, view, ImageResolution=[200, 200], FrameWindow=[0, 2])
    frames = [os.path.join(out, "%s.%04d.png" % (name, i)) for i in range(3)]
    scene.AnimationTime = 0.5
    middle = display.ClipPosition[0]
    scene.AnimationTime = 0.0
    track.KeyFrames = []
    return frames, middle


frames, middle = animate("moving", 40.0, 150.0)
check(all(os.path.exists(f) for f in frames), "SaveAnimation wrote 3 frames: %s" % frames)
check(abs(middle - 95.0) < 1e-6, "at time 0.5 Clip Position x is interpolated: %s" % middle)
if all(os.path.exists(f) for f in frames):
    a, b, c = (pixels(f) for f in frames)
    check((a != b).any() and (b != c).any() and (a != c).any(),
          "the three frames differ (the clip moved): %d, %d pixels changed"
          % ((a != b).any(axis=1).sum(), (b != c).any(axis=1).sum()))
still, _ = animate("still", 95.0, 95.0)
if all(os.path.exists(f) for f in still):
    a, b, c = (pixels(f) for f in still)
    check(not (a != b).any() and not (b != c).any(),
          "negative control: a track holding one value gives identical frames")
print("%d failure(s)" % len(failures))
sys.stdout.flush()
os._exit(1 if failures else 0)  # (teardown under Xvfb: see TestSameLook.py)

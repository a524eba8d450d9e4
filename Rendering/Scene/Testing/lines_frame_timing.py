"""The frame cost of line AO in the Render View (Contextual AO) (docs/lines.md's
table): carotid.vtk streamlines of SEEDS Stream Tracer seeds drawn as lines
2 pixels wide, at WxH; per frame the wall time of Render and the pass's
stages: no AO, the first line AO frame, a still view, a camera turn, a
colour change, a dolly, three steps of a camera drag (interactive renders)
and the still render at its release.

  PYTHONPATH=build/python xvfb-run -a -s "-screen 0 2000x1200x24" pvpython --dr \
    lines_frame_timing.py PLUGIN.so DATA_DIR SEEDS WxH [BACKEND]

BACKEND: the view's Surface AO Backend (Auto, CPU or OpenGL; default Auto).
"""
import json
import os
import sys
import time

from paraview.simple import *  # noqa: F401,F403
LoadPlugin(sys.argv[1], remote=False, ns=globals())
import contextualao  # noqa: E402,F401
data, seeds = sys.argv[2], int(sys.argv[3])
W, H = [int(v) for v in sys.argv[4].split("x")]
view = CreateView("ContextualAORenderView")
view.OrientationAxesVisibility = 0
view.ViewSize = [W, H]
view.LineAOMethod = 0
view.SurfaceAOMethod = "None"
view.SurfaceAOBackend = sys.argv[5] if len(sys.argv) > 5 else "Auto"
carotid = LegacyVTKReader(FileNames=[os.path.join(data, "carotid.vtk")])
tracer = StreamTracer(Input=carotid, SeedType="Point Cloud")
tracer.Vectors = ["POINTS", "vectors"]
tracer.SeedType.Center = [137.0, 104.0, 23.0]
tracer.SeedType.Radius = 12.0
tracer.SeedType.NumberOfPoints = seeds
tracer.MaximumStreamlineLength = 200.0
lines = Show(tracer, view)
ColorBy(lines, None)
lines.LineWidth = 2.0
view.CameraPosition = [137.5, 40.0, 70.0]
view.CameraFocalPoint = [137.5, 104.0, 20.0]
view.CameraViewUp = [0, 0, 1]
ResetCamera(view)
chain = view.GetRenderer().GetPass()
while chain.GetClassName() != "vtkContextualAOPass":
    chain = chain.GetDelegatePass()


def frame(label, interactive=False):
    t = time.perf_counter()
    if interactive:
        view.SMProxy.InteractiveRender()
    else:
        Render(view)
    ms = 1000 * (time.perf_counter() - t)
    r = json.loads(chain.GetLastFrameReport())
    stages = ", ".join("%s %.0f" % (k, v) for k, v in r["stages"].items())
    line = r.get("lines", {})
    print("| %d | %dx%d | %s | %.0f | %s | %d | %s |" % (line.get("segments", 0), W, H, label, ms, stages,
                                                       line.get("pixels", 0), line.get("ao", "")))


print("| segments | image | frame | ms | stages (ms) | line pixels | line AO on |")
print("|---:|---|---|---:|---|---:|---|")
frame("no AO (Method None)")
view.SurfaceAOMethod = "Voxel Cones"
view.LineAOMethod = 1
frame("first line AO frame")
frame("still view")
view.GetActiveCamera().Azimuth(10)
frame("camera turn 10 deg")
lines.AmbientColor = lines.DiffuseColor = [0.6, 0.9, 0.95]
frame("colour change")
view.GetActiveCamera().Dolly(1.2)
frame("dolly 1.2")
# A camera drag's steps (interactive renders; the LOD threshold raised so
# that ParaView draws the lines themselves, not a decimated copy): the
# lines' grid of the last still frame is kept.
view.LODThreshold = 1.0e6
for step in range(3):
    view.GetActiveCamera().Azimuth(3)
    frame("drag step %d (interactive, 3 deg)" % (step + 1), interactive=True)
frame("release (still)")

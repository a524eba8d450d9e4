"""Line AO's frame cost against line count and image size in the Render
View (Contextual AO) (docs/lines.md's scale table): streamlines of FIELD
(a legacy .vtk with point vectors, or a PLOT3D xyz .bin whose q file is
the same name with "xyz" replaced by "q", traced through its Momentum) from
SEEDS Stream Tracer seeds in a point cloud over the field's middle, drawn
as lines 1 pixel wide, at each image size. One row per size: the no-AO
frame, the first line AO frame, a camera turn, a colour change (ms per
Render), and the first frame's ratio to the no-AO one.

  PYTHONPATH=build/python xvfb-run -a -s "-screen 0 2000x1200x24" pvpython --dr \\
    lines_scale_timing.py PLUGIN.so FIELD SEEDS WxH [WxH ...]
"""
import json
import os
import sys
import time

from paraview.simple import *  # noqa: F401,F403

LoadPlugin(sys.argv[1], remote=False, ns=globals())
import contextualao  # noqa: E402,F401

field, seeds, sizes = sys.argv[2], int(sys.argv[3]), sys.argv[4:]
if field.endswith(".bin"):
    reader = PLOT3DReader(FileName=field, QFileName=[field.replace("xyz", "q")])
    vectors = ["POINTS", "Momentum"]
    source = MergeBlocks(Input=reader)
else:
    source = LegacyVTKReader(FileNames=[field])
    source.UpdatePipeline()
    vectors = ["POINTS", source.PointData.keys()[[a.GetNumberOfComponents() for a in
                                                  source.PointData.values()].index(3)]]
source.UpdatePipeline()
b = source.GetDataInformation().GetBounds()
diagonal = sum((b[2 * d + 1] - b[2 * d]) ** 2 for d in range(3)) ** 0.5
tracer = StreamTracer(Input=source, SeedType="Point Cloud")
tracer.Vectors = vectors
tracer.SeedType.Center = [0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5])]
tracer.SeedType.Radius = 0.3 * diagonal
tracer.SeedType.NumberOfPoints = seeds
tracer.MaximumStreamlineLength = diagonal
view = CreateView("ContextualAORenderView")
view.OrientationAxesVisibility = 0
view.LineAOMethod = 0
view.SurfaceAOMethod = "None"
lines = Show(tracer, view)
ColorBy(lines, None)
lines.LineWidth = 1.0
chain = view.GetRenderer().GetPass()
while chain.GetClassName() != "vtkContextualAOPass":
    chain = chain.GetDelegatePass()


def timed():
    t = time.perf_counter()
    Render(view)
    return 1000 * (time.perf_counter() - t)


print("| field | seeds | segments | image | no AO ms | first AO frame ms | camera turn ms | colour change ms "
      "| first / no AO | the first frame's stages (ms) |")
print("|---|---:|---:|---|---:|---:|---:|---:|---:|---|")
for size in sizes:
    view.ViewSize = [int(v) for v in size.split("x")]
    view.LineAOMethod = 0
    view.SurfaceAOMethod = "None"
    view.CameraPosition = [tracer.SeedType.Center[0] - diagonal, tracer.SeedType.Center[1] - diagonal,
                           tracer.SeedType.Center[2] + diagonal]
    view.CameraFocalPoint = tracer.SeedType.Center
    view.CameraViewUp = [0, 0, 1]
    ResetCamera(view)
    timed()
    plain = timed()
    view.SurfaceAOMethod = "Voxel Cones"
    view.LineAOMethod = 1
    first = timed()
    report = json.loads(chain.GetLastFrameReport())
    view.GetActiveCamera().Azimuth(10)
    turn = timed()
    lines.AmbientColor = lines.DiffuseColor = [0.2 + 0.6 * (sizes.index(size) % 2), 0.8, 0.9]
    colour = timed()
    stages = ", ".join("%s %.0f" % (k, v) for k, v in report["stages"].items())
    print("| %s | %d | %d | %s | %.0f | %.0f | %.0f | %.0f | %.1f | %s |" % (
        os.path.basename(field), seeds, report.get("lines", {}).get("segments", 0), size, plain, first, turn,
        colour, first / plain, stages))

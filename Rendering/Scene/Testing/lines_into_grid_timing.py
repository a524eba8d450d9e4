"""What the lines cost the surfaces' grid (docs/lines.md): carotid.vtk's
isosurface at 200 and 300 streamlines drawn as lines 2 pixels wide, in the
project's EGL window at 800x600, voxel cones on the world grid; per
backend (CPU, then OpenGL) its first frame and the frame after the lines moved,
with the pass's stages ("lines_into_grid": the lines ORed into the
surfaces' grid; on OpenGL the grid read back and put back too).

  PYTHONPATH=build/python /usr/bin/python3 \\
      Rendering/Scene/Testing/lines_into_grid_timing.py Data/carotid.vtk
"""
import json
import sys
import time

from contextualao import vtkContextualAOEGLWindow, vtkContextualAOPass
from vtkmodules.vtkFiltersCore import vtkContourFilter
from vtkmodules.vtkFiltersFlowPaths import vtkStreamTracer
from vtkmodules.vtkFiltersSources import vtkPointSource
from vtkmodules.vtkIOLegacy import vtkDataSetReader
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper, vtkRenderer
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401

reader = vtkDataSetReader()
reader.SetFileName(sys.argv[1])
reader.Update()
b = reader.GetOutput().GetBounds()
iso = vtkContourFilter()
iso.SetInputConnection(reader.GetOutputPort())
iso.SetValue(0, 200.0)
iso.Update()
seeds = vtkPointSource()
seeds.SetNumberOfPoints(300)
seeds.SetCenter((b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2)
seeds.SetRadius(0.25 * (b[1] - b[0]))
tracer = vtkStreamTracer()
tracer.SetInputConnection(reader.GetOutputPort())
tracer.SetSourceConnection(seeds.GetOutputPort())
tracer.SetMaximumPropagation(200)
tracer.SetIntegrationDirectionToBoth()
tracer.Update()
print("isosurface: %d triangles; streamlines: %d points" % (iso.GetOutput().GetNumberOfCells(),
                                                           tracer.GetOutput().GetNumberOfPoints()))
print("| backend | frame | ms | stages (ms) |\n|---|---|---:|---|")
renderer = vtkRenderer()
actors = []
for source in (iso, tracer):
    mapper = vtkPolyDataMapper()
    mapper.SetInputConnection(source.GetOutputPort())
    mapper.ScalarVisibilityOff()
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetLineWidth(2)
    renderer.AddActor(actor)
    actors.append(actor)
window = vtkContextualAOEGLWindow()
window.SetSize(800, 600)
window.AddRenderer(renderer)
aoPass = vtkContextualAOPass()
renderer.SetPass(aoPass)
renderer.ResetCamera()
for backend, name in ((vtkContextualAOPass.BACKEND_CPU, "CPU"), (vtkContextualAOPass.BACKEND_OPENGL, "OpenGL")):
    aoPass.SetBackend(backend)
    for frame in ("first on the backend", "lines moved"):
        if frame == "lines moved":
            actors[1].AddPosition(0.01 * (b[1] - b[0]), 0.0, 0.0)
        start = time.perf_counter()
        window.Render()
        ms = 1000.0 * (time.perf_counter() - start)
        report = json.loads(aoPass.GetLastFrameReport())
        stages = ", ".join("%s %.0f" % (k, v) for k, v in report["stages"].items())
        print("| %s | %s | %.0f | %s |" % (name, frame, ms, stages))

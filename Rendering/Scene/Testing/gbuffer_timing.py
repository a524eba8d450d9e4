"""The pass's two G-buffers timed at 1920 x 1080 (docs/surface-benchmarks.md's table):
42400-IDGH.stl tiled COPIES times in the project's EGL window, whole-colour
AO, three camera turns per G-buffer, the last frame's report printed.

  PYTHONPATH=build/python /usr/bin/python3 Rendering/Scene/Testing/gbuffer_timing.py COPIES [STL]
"""
import sys, time
import contextualao
from contextualao import vtkContextualAOPass, vtkContextualAOEGLWindow
from vtkmodules.vtkRenderingCore import vtkRenderer, vtkActor, vtkPolyDataMapper
from vtkmodules.vtkIOGeometry import vtkSTLReader
import vtkmodules.vtkRenderingOpenGL2
w = vtkContextualAOEGLWindow(); w.SetSize(1920, 1080)
r = vtkRenderer(); w.AddRenderer(r)
rd = vtkSTLReader(); rd.SetFileName(sys.argv[2] if len(sys.argv) > 2 else "../shared/data/42400-IDGH.stl"); rd.Update()
b = rd.GetOutput().GetBounds(); pitch = 1.1 * max(b[1]-b[0], b[3]-b[2])
copies = int(sys.argv[1])
k = int(round(copies ** 0.5))
for c in range(copies):
    m = vtkPolyDataMapper(); m.SetInputConnection(rd.GetOutputPort()); a = vtkActor(); a.SetMapper(m)
    a.SetPosition((c % k) * pitch, (c // k) * pitch, 0); r.AddActor(a)
r.ResetCamera(); r.GetActiveCamera().Elevation(30); r.GetActiveCamera().Azimuth(30); r.ResetCameraClippingRange()
p = vtkContextualAOPass(); p.SetApplyTo(1); r.SetPass(p)
for gb, name in ((0, "ray cast"), (1, "depth buffer")):
    p.SetGBuffer(gb)
    for rep in range(3):
        r.GetActiveCamera().Azimuth(1); r.ResetCameraClippingRange()
        t = time.time(); w.Render(); dt = (time.time() - t) * 1000
    print(copies, "copies", name, "frame ms %.0f" % dt, p.GetLastFrameReport()[:260])

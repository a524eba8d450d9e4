"""docs/surfaces.md's picture of vtkContextualAOPass: Data/Bunny.vtp on a slab in
the project's EGL window (Ambient 0.4, Diffuse 0.6), the pass off (Method
NONE), on the ambient term (the pass's default) and on the whole colour,
written to OUT_DIR/pass-off.png, pass-ambient.png and pass-whole.png.

  PYTHONPATH=build/python /usr/bin/python3 Rendering/Scene/Testing/pass_screenshot.py OUT_DIR
"""
import os
import sys

import contextualao
from contextualao import vtkContextualAOPass, vtkContextualAOEGLWindow
from vtkmodules.vtkRenderingCore import vtkRenderer, vtkActor, vtkPolyDataMapper, vtkWindowToImageFilter
from vtkmodules.vtkFiltersSources import vtkCubeSource
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkmodules.vtkIOImage import vtkPNGWriter
import vtkmodules.vtkRenderingOpenGL2
w = vtkContextualAOEGLWindow(); w.SetSize(400, 300)
r = vtkRenderer(); r.SetBackground(1, 1, 1); w.AddRenderer(r)
rd = vtkXMLPolyDataReader(); rd.SetFileName(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "Data", "Bunny.vtp")); rd.Update()
b = rd.GetOutput().GetBounds()
slab = vtkCubeSource(); slab.SetBounds(b[0]-0.1, b[1]+0.1, b[2]-0.02, b[2], b[4]-0.1, b[5]+0.1)
for src in (rd, slab):
    m = vtkPolyDataMapper(); m.SetInputConnection(src.GetOutputPort()); a = vtkActor(); a.SetMapper(m); r.AddActor(a)
    a.GetProperty().SetAmbient(0.4); a.GetProperty().SetDiffuse(0.6)
r.ResetCamera(); r.GetActiveCamera().Elevation(25); r.GetActiveCamera().Azimuth(20); r.ResetCameraClippingRange()
p = vtkContextualAOPass(); r.SetPass(p)
for name, method, apply in (("off", 0, 0), ("ambient", 1, 0), ("whole", 1, 1)):
    p.SetMethod(method); p.SetApplyTo(apply); w.Render()
    f = vtkWindowToImageFilter(); f.SetInput(w); f.ReadFrontBufferOff(); f.Update()
    wr = vtkPNGWriter(); wr.SetFileName(os.path.join(sys.argv[1], "pass-%s.png" % name)); wr.SetInputConnection(f.GetOutputPort()); wr.Write()
    print(name, p.GetLastFrameReport())

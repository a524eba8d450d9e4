"""The README's picture of vtkContextualAOPass: Data/Bunny.vtp on a slab in
the project's EGL window, the pass off (Method NONE) and on (VCT), written
to OUT_DIR/pass-off.png and pass-on.png.

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
r.ResetCamera(); r.GetActiveCamera().Elevation(25); r.GetActiveCamera().Azimuth(20); r.ResetCameraClippingRange()
p = vtkContextualAOPass(); r.SetPass(p)
for name, method in (("off", 0), ("on", 1)):
    p.SetMethod(method); w.Render()
    f = vtkWindowToImageFilter(); f.SetInput(w); f.ReadFrontBufferOff(); f.Update()
    wr = vtkPNGWriter(); wr.SetFileName(os.path.join(sys.argv[1], "pass-%s.png" % name)); wr.SetInputConnection(f.GetOutputPort()); wr.Write()
    print(name, p.GetLastFrameReport())

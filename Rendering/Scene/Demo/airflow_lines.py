"""The airflow scene: streamlines of Data/kitchen.vtk (air flowing among the
furniture of a kitchen) drawn as lines 2 pixels wide in the ParaView view
"Render View (Contextual AO)": AO off | Line AO | Line AO with the
Mallo-Banks line shading, side by side in one PNG.

  PYTHONPATH=build/python xvfb-run -a -s "-screen 0 2000x1200x24" pvpython --dr \\
      Rendering/Scene/Demo/airflow_lines.py \\
      build/lib/paraview-5.11/plugins/ContextualAO/ContextualAO.so Data/kitchen.vtk OUT.png
"""
import os
import sys
import tempfile

from paraview.simple import *  # noqa: F401,F403
from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter
from vtkmodules.vtkFiltersCore import vtkImageAppend

LoadPlugin(sys.argv[1], remote=False, ns=globals())
reader = LegacyVTKReader(FileNames=[sys.argv[2]])
reader.UpdatePipeline()
b = reader.GetDataInformation().GetBounds()
tracer = StreamTracer(Input=reader, SeedType="Point Cloud")
tracer.Vectors = ["POINTS", "velocity"]
tracer.SeedType.Center = [(b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2]
tracer.SeedType.Radius = 0.3 * (b[1] - b[0])
tracer.SeedType.NumberOfPoints = 200
view = CreateView("ContextualAORenderView")
view.ViewSize = [480, 400]
view.OrientationAxesVisibility = 0
display = Show(tracer, view)
display.ColorArrayName = ["POINTS", ""]
display.DiffuseColor = [0.95, 0.85, 0.6]
display.AmbientColor = [0.95, 0.85, 0.6]
display.LineWidth = 2
display.Specular = 0.3
view.CameraPosition = [b[1] + 1.5, b[2] - 2.5, b[5] + 2.0]
view.CameraFocalPoint = [(b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2]
view.CameraViewUp = [0.0, 0.0, 1.0]
view.ResetCamera()
GetActiveCamera().Dolly(1.25)  # (the reset fits the bounding sphere: the lines fill more of the frame)
panels = vtkImageAppend()
with tempfile.TemporaryDirectory() as tmp:
    # (Surface AO Method None leaves the lines their Line AO: one technique
    # per kind of geometry. AO off is both None.)
    for name, method, lines, shading in (("off", "None", "None", "As Drawn"),
                                         ("ao", "Voxel Cones", "Voxelized Lines", "As Drawn"),
                                         ("shaded", "Voxel Cones", "Voxelized Lines", "Mallo-Banks")):
        view.SurfaceAOMethod = method
        view.LineAOMethod = lines
        view.LineShading = shading
        path = os.path.join(tmp, name + ".png")
        SaveScreenshot(path, view, ImageResolution=[480, 400])
        png = vtkPNGReader()
        png.SetFileName(path)
        png.Update()
        panels.AddInputData(png.GetOutput())
    panels.SetAppendAxis(0)
    panels.Update()
writer = vtkPNGWriter()
writer.SetFileName(sys.argv[3])
writer.SetInputData(panels.GetOutput())
writer.Write()
print("wrote %s" % sys.argv[3])

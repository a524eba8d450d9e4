"""Writes platform.vtp: a flat plate with a slanted blade and a cylinder
standing on it (closed boxes and a capped cylinder, triangulated), the
scene where voxel cone tracing drew contour bands around the blade on the
plate (docs/surface-benchmarks.md, "Bands"). Run with /usr/bin/python3:

    /usr/bin/python3 Rendering/Tool/Benchmark/platform_mesh.py OUT.vtp
"""
import sys

from vtkmodules.vtkCommonTransforms import vtkTransform
from vtkmodules.vtkFiltersCore import vtkAppendPolyData, vtkTriangleFilter
from vtkmodules.vtkFiltersGeneral import vtkTransformPolyDataFilter
from vtkmodules.vtkFiltersSources import vtkCubeSource, vtkCylinderSource
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

plate = vtkCubeSource()
plate.SetBounds(-5, 5, -5, 5, -0.5, 0)
blade = vtkCubeSource()
blade.SetBounds(-0.4, 0.4, -3, 3, 0, 4)
turn = vtkTransform()
turn.RotateZ(25)
turn.RotateY(12)
slanted = vtkTransformPolyDataFilter()
slanted.SetInputConnection(blade.GetOutputPort())
slanted.SetTransform(turn)
cylinder = vtkCylinderSource()
cylinder.SetResolution(48)
cylinder.SetRadius(0.7)
cylinder.SetHeight(3)
cylinder.CappingOn()
place = vtkTransform()
place.Translate(3, -3, 1.5)
place.RotateX(90)
placed = vtkTransformPolyDataFilter()
placed.SetInputConnection(cylinder.GetOutputPort())
placed.SetTransform(place)
scene = vtkAppendPolyData()
for part in (plate, slanted, placed):
    triangles = vtkTriangleFilter()
    triangles.SetInputConnection(part.GetOutputPort())
    triangles.Update()
    scene.AddInputData(triangles.GetOutput())
scene.Update()
writer = vtkXMLPolyDataWriter()
writer.SetFileName(sys.argv[1] if len(sys.argv) > 1 else "platform.vtp")
writer.SetInputData(scene.GetOutput())
writer.Write()

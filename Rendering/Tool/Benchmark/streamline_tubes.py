"""Writes a dense scene of streamline tubes: carotid.vtk's vectors traced
from 300 random points within 8 of (137, 104, 23), Runge-Kutta 4 with steps
of 0.8 (world units) in both directions (each line at most 500 long), tubes of
radius 0.25 with 6
sides, triangulated: 1 360 674 points, 2 714 148 triangles
(docs/surface-benchmarks.md, "Dense meshes"). Run with /usr/bin/python3:

    /usr/bin/python3 Rendering/Tool/Benchmark/streamline_tubes.py ../shared/data/carotid.vtk OUT.vtp
"""
import sys

from vtkmodules.vtkFiltersCore import vtkTriangleFilter, vtkTubeFilter
from vtkmodules.vtkFiltersFlowPaths import vtkStreamTracer
from vtkmodules.vtkFiltersSources import vtkPointSource
from vtkmodules.vtkIOLegacy import vtkStructuredPointsReader
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

reader = vtkStructuredPointsReader()
reader.SetFileName(sys.argv[1])
seeds = vtkPointSource()
seeds.SetNumberOfPoints(300)
seeds.SetCenter(137, 104, 23)
seeds.SetRadius(8)
lines = vtkStreamTracer()
lines.SetInputConnection(reader.GetOutputPort())
lines.SetSourceConnection(seeds.GetOutputPort())
lines.SetIntegratorTypeToRungeKutta4()
lines.SetInitialIntegrationStep(0.8)
lines.SetIntegrationStepUnit(vtkStreamTracer.LENGTH_UNIT)
lines.SetMaximumPropagation(500)
lines.SetIntegrationDirectionToBoth()
tubes = vtkTubeFilter()
tubes.SetInputConnection(lines.GetOutputPort())
tubes.SetRadius(0.25)
tubes.SetNumberOfSides(6)
triangles = vtkTriangleFilter()
triangles.SetInputConnection(tubes.GetOutputPort())
triangles.Update()
writer = vtkXMLPolyDataWriter()
writer.SetFileName(sys.argv[2])
writer.SetInputData(triangles.GetOutput())
writer.Write()

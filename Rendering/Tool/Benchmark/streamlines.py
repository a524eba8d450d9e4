"""Writes streamlines (polylines, no tubes) of any VTK vector field: N seeds
drawn (seeded random, without repeats) from the field's points whose speed
is above the median of the non-zero speeds, traced both ways by
Runge-Kutta 4-5 (at most 200 long, initial step 0.5 cell lengths). The
line inputs of docs/lines.md. Run with /usr/bin/python3:

    /usr/bin/python3 Rendering/Tool/Benchmark/streamlines.py FIELD.vtk OUT.vtp N
"""
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkFiltersFlowPaths import vtkStreamTracer
from vtkmodules.vtkIOLegacy import vtkDataSetReader
from lines_file import write_lines

source, output, count = sys.argv[1], sys.argv[2], int(sys.argv[3])
reader = vtkDataSetReader()
reader.SetFileName(source)
reader.Update()
field = reader.GetOutput()
vectors = field.GetPointData().GetVectors()
if vectors is None:
    sys.exit("%s has no point vectors" % source)
speed = np.linalg.norm(vtk_to_numpy(vectors), axis=1)
candidates = np.nonzero(speed > np.percentile(speed[speed > 0], 50))[0]
picked = np.random.default_rng(1).choice(candidates, size=min(count, len(candidates)), replace=False)
points = vtkPoints()
for i in picked:
    points.InsertNextPoint(field.GetPoint(int(i)))
seeds = vtkPolyData()
seeds.SetPoints(points)
tracer = vtkStreamTracer()
tracer.SetInputData(field)
tracer.SetSourceData(seeds)
tracer.SetMaximumPropagation(200)
tracer.SetIntegrationDirectionToBoth()
tracer.SetIntegratorTypeToRungeKutta45()
tracer.SetInitialIntegrationStep(0.5)
tracer.SetMaximumNumberOfSteps(4000)
tracer.Update()
lines = write_lines(tracer.GetOutput(), output)
print("%s: %d lines, %d points" % (output, lines.GetNumberOfLines(), lines.GetNumberOfPoints()))

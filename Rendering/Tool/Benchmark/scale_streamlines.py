"""Writes the streamlines of docs/lines.md's scale table as a small .vtp
(points and lines only, zlib-compressed), for `cao bench surface-frame` and
`cao bench lines` where pvpython is not at hand (a GPU machine): FIELD (a
legacy .vtk with point vectors, or a PLOT3D xyz .bin whose q file is the
same name with "xyz" replaced by "q", traced through its Momentum), SEEDS
seeds in a point cloud over the field's middle (radius 0.3 of its
diagonal), traced both ways up to a diagonal long, as
Rendering/Scene/Testing/lines_scale_timing.py does in ParaView (ParaView's
Stream Tracer defaults). The cloud's random points are VTK's, so the
segment count is close to, not equal to, that script's. Run with
/usr/bin/python3:

    /usr/bin/python3 Rendering/Tool/Benchmark/scale_streamlines.py FIELD OUT.vtp SEEDS
"""
import sys

from vtkmodules.vtkFiltersCore import vtkAppendFilter
from vtkmodules.vtkFiltersFlowPaths import vtkStreamTracer
from vtkmodules.vtkFiltersSources import vtkPointSource
from vtkmodules.vtkIOLegacy import vtkDataSetReader
from vtkmodules.vtkIOParallel import vtkMultiBlockPLOT3DReader
from lines_file import write_lines

field_path, output, seeds = sys.argv[1], sys.argv[2], int(sys.argv[3])
if field_path.endswith(".bin"):
    reader = vtkMultiBlockPLOT3DReader()
    reader.SetXYZFileName(field_path)
    reader.SetQFileName(field_path.replace("xyz", "q"))
    reader.AddFunction(202)  # momentum
    reader.Update()
    merge = vtkAppendFilter()
    blocks = reader.GetOutput()
    for b in range(blocks.GetNumberOfBlocks()):
        merge.AddInputData(blocks.GetBlock(b))
    merge.Update()
    field = merge.GetOutput()
    field.GetPointData().SetActiveVectors("Momentum")
else:
    reader = vtkDataSetReader()
    reader.SetFileName(field_path)
    reader.Update()
    field = reader.GetOutput()
if field.GetPointData().GetVectors() is None:
    sys.exit("%s has no point vectors" % field_path)
b = field.GetBounds()
diagonal = sum((b[2 * d + 1] - b[2 * d]) ** 2 for d in range(3)) ** 0.5
cloud = vtkPointSource()
cloud.SetCenter(0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]))
cloud.SetRadius(0.3 * diagonal)
cloud.SetNumberOfPoints(seeds)
tracer = vtkStreamTracer()
tracer.SetInputData(field)
tracer.SetSourceConnection(cloud.GetOutputPort())
tracer.SetMaximumPropagation(diagonal)
tracer.SetIntegrationDirectionToBoth()
tracer.SetIntegratorTypeToRungeKutta45()
tracer.Update()
lines = write_lines(tracer.GetOutput(), output)
n = lines.GetLines().GetNumberOfConnectivityIds() - lines.GetNumberOfLines()
print("%s: %d lines, %d segments" % (output, lines.GetNumberOfLines(), n))

"""Writes streamlines (polylines, no tubes) of an Exodus II file's point
vector field, for `cao bench lines`: SEEDS seeds in a point cloud (VTK's
vtkPointSource, radius 0.3 of the first block's diagonal, at its centre),
traced both ways up to a diagonal long (vtkStreamTracer's defaults
otherwise), as scale_streamlines.py does for legacy and PLOT3D fields. The
held-out scene of docs/lines.md's "Where a line voxel starts to dim a
ray" (disk_out_ref.ex2, its V field). Run with /usr/bin/python3:

    /usr/bin/python3 Rendering/Tool/Benchmark/exodus_streamlines.py FILE.ex2 VECTORS OUT.vtp SEEDS
"""
import math
import sys

from vtkmodules.vtkFiltersFlowPaths import vtkStreamTracer
from vtkmodules.vtkFiltersSources import vtkPointSource
from vtkmodules.vtkIOExodus import vtkExodusIIReader
from lines_file import write_lines

source, vectors, output, count = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
reader = vtkExodusIIReader()
reader.SetFileName(source)
reader.UpdateInformation()
reader.SetAllArrayStatus(vtkExodusIIReader.NODAL, 1)
reader.Update()
field = reader.GetOutput().GetBlock(0).GetBlock(0)
if field is None or field.GetPointData().GetArray(vectors) is None:
    sys.exit("%s: no point array %s in its first block" % (source, vectors))
b = field.GetBounds()
diagonal = math.sqrt((b[1] - b[0]) ** 2 + (b[3] - b[2]) ** 2 + (b[5] - b[4]) ** 2)
seeds = vtkPointSource()
seeds.SetCenter((b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2)
seeds.SetRadius(0.3 * diagonal)
seeds.SetNumberOfPoints(count)
tracer = vtkStreamTracer()
tracer.SetInputData(field)
tracer.SetSourceConnection(seeds.GetOutputPort())
tracer.SetInputArrayToProcess(0, 0, 0, 0, vectors)
tracer.SetIntegrationDirectionToBoth()
tracer.SetMaximumPropagation(diagonal)
tracer.Update()
lines = write_lines(tracer.GetOutput(), output)
print("%s: %d lines, %d points" % (output, tracer.GetOutput().GetNumberOfCells(), tracer.GetOutput().GetNumberOfPoints()))

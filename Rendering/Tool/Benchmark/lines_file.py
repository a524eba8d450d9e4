"""The line files of docs/lines.md's benchmarks, written one way: a
tracer's points and lines only (cao reads nothing else), as a
zlib-compressed .vtp. Imported by streamlines.py and scale_streamlines.py
(beside them)."""
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter


def write_lines(traced, path):
    """Writes `traced`'s points and lines to `path`; returns the lines."""
    lines = vtkPolyData()
    lines.SetPoints(traced.GetPoints())
    lines.SetLines(traced.GetLines())
    writer = vtkXMLPolyDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(lines)
    writer.SetDataModeToAppended()
    writer.SetCompressorTypeToZLib()
    writer.Write()
    return lines

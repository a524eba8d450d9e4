"""Repeated opacity edits against full recomputes, in one run of one
vtkLocalAmbientOcclusion, as a user editing the transfer function makes
them (the first edit pays for new buffers; later ones reuse them):

  /usr/bin/python3 opacity_edits.py VOLUME [--rays 26] [--threads 1] [--edits 4]

The opacity alternates between two maps: --from (0 up to a quarter of the
scalar range, then a ramp to 0.8) and --to (the ramp raised over the top
quarter), the `cao tf` case. Then two full recomputes of the same settings
(the scalars marked modified), so both sides reuse their buffers. Prints a
table: milliseconds, voxels recomputed, and each edit's speed-up over the
mean full recompute as a share of its limit (all / recomputed). No
assertion: a table to read (docs/interaction.md has measured ones).
Needs the build's python/ on PYTHONPATH (or next to this source tree's
build/)."""
import argparse
import os
import statistics
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, os.pardir, os.pardir, os.pardir, "build", "python"))
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction  # noqa: E402

import contextualao as cao  # noqa: E402

parser = argparse.ArgumentParser()
parser.add_argument("volume")
parser.add_argument("--rays", type=int, choices=(6, 14, 26), default=26)
parser.add_argument("--threads", type=int, default=1)
parser.add_argument("--edits", type=int, default=4)
args = parser.parse_args()

reader = cao.vtkCAOSLCReader() if args.volume.endswith(".slc") else None
if reader is None:
    from vtkmodules.vtkIOLegacy import vtkDataSetReader
    from vtkmodules.vtkIOImage import vtkMetaImageReader
    from vtkmodules.vtkIOXML import vtkXMLImageDataReader
    ext = os.path.splitext(args.volume)[1]
    reader = {".vti": vtkXMLImageDataReader, ".mhd": vtkMetaImageReader,
              ".mha": vtkMetaImageReader}.get(ext, vtkDataSetReader)()
reader.SetFileName(args.volume)
reader.Update()
volume = reader.GetOutput()
lo, hi = volume.GetPointData().GetScalars().GetRange()
q = lambda f: lo + f * (hi - lo)  # noqa: E731
maps = {"from": [q(0), 0, q(0.25), 0, q(1), 0.8],
        "to": [q(0), 0, q(0.25), 0, q(0.75), 0.6, q(1), 1]}


def function(points):
    f = vtkPiecewiseFunction()
    for i in range(0, len(points), 2):
        f.AddPoint(points[i], points[i + 1])
    return f


lao = cao.vtkLocalAmbientOcclusion()
lao.SetInputData(volume)
lao.SetQualityToCustom()
lao.SetRayPattern({6: lao.RAYS_6, 14: lao.RAYS_14, 26: lao.RAYS_26}[args.rays])
lao.SetNumberOfThreads(args.threads)
lao.SetBackendToCPU()
voxels = volume.GetNumberOfPoints()
rows = []


def run(what):
    start = time.perf_counter()
    lao.Update()
    ms = 1000.0 * (time.perf_counter() - start)
    fd = lao.GetOutput().GetFieldData()
    rows.append((what, fd.GetAbstractArray("LAOUpdate").GetValue(0), ms,
                 fd.GetArray("LAOUpdateVoxels").GetComponent(0, 1)))


lao.SetOpacityFunction(function(maps["from"]))
run("first run (--from)")
for e in range(args.edits):
    name = "to" if e % 2 == 0 else "from"
    lao.SetOpacityFunction(function(maps[name]))
    run("edit %d (--%s)" % (e + 1, name))
for r in range(2):
    volume.GetPointData().GetScalars().Modified()
    run("full recompute %d (--%s)" % (r + 1, name))
full = statistics.mean(ms for what, _, ms, _ in rows if what.startswith("full recompute"))
print("%s, %d voxels, %d rays, %d thread(s); full recompute (mean of the last two): %.1f ms"
      % (args.volume, voxels, args.rays, args.threads, full))
print("| run | what ran | ms | voxels recomputed | speed-up over a full recompute | share of the limit |")
print("|---|---|---:|---:|---:|---:|")
for what, reason, ms, recomputed in rows:
    edit = reason == "opacity edit"
    print("| %s | %s | %.1f | %.0f | %s | %s |" % (
        what, reason, ms, recomputed, "%.2f" % (full / ms) if edit else "",
        "%.2f" % ((full / ms) / (voxels / recomputed)) if edit and recomputed > 0 else ""))

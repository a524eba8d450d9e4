"""Distributed LAO and CAO on ParaView's MPI engine:

    mpirun -np 2 pvbatch TestMPILAO.py PLUGIN.so OUTPUT_DIR

Each rank computes the LAO of its piece of a real volume
(Data/hydrogen.vti); the filter asks the pipeline for ghost voxels (the
reach plus the trilinear footprint), so a piece's AO must equal the serial
AO of the same voxels. The pieces are written in parallel (.pvti) and read
back on rank 0, where the same LAO is computed serially with the VTK
filter; every voxel must be identical, and the volume must really have been
split (as many pieces as ranks, each smaller than the whole)."""
import os
import sys

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

plugin, outdir = sys.argv[1], sys.argv[2]
data = os.environ["CAO_DATA_DIR"]
LoadPlugin(plugin, remote=False, ns=globals())
ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mpi_view_checks import check, finish  # noqa: E402


reader = OpenDataFile(os.path.join(data, "hydrogen.vti"))
lao = LocalAmbientOcclusion(Input=reader)
lao.Quality = "Custom"  # the settings below apply
lao.RayPattern = "26 rays (faces + edges + corners)"
lao.Backend = "CPU"
# An explicit opacity function: without one the filter ramps over the
# scalar range of the data it holds, which in parallel is the piece's.
opacity = GetOpacityTransferFunction("probability_density")
opacity.Points = [0.0, 0.0, 0.5, 0.0, 0.05, 0.1, 0.5, 0.0, 0.4, 0.9, 0.5, 0.0]
lao.OpacityFunction = opacity
path = os.path.join(outdir, "hydrogen-lao.pvti")
# Inline binary: the default appended mode wrote files ParaView 5.11's
# reader rejected (see the cao tool's writer).
SaveData(path, proxy=lao, PointDataArrays=["AmbientOcclusion"], DataMode="Binary")
import time  # noqa: E402


def wait_for_pieces(name):
    """The other rank may still be writing its piece: wait until all are complete."""
    piece_dir = os.path.join(outdir, name)
    deadline = time.time() + 60
    while time.time() < deadline:
        files = [os.path.join(piece_dir, f) for f in os.listdir(piece_dir)] \
            if os.path.isdir(piece_dir) else []
        if len(files) == ranks and all(open(f, "rb").read().rstrip().endswith(b"</VTKFile>")
                                       for f in files):
            return
        time.sleep(0.2)


wait_for_pieces("hydrogen-lao")
# Contextual AO downstream, distributed the same way (the depth maps whole
# on every rank).
sphere = Sphere(Radius=14.0, ThetaResolution=32, PhiResolution=16)
maps = ClipDepthMaps(Input=sphere, Reach=8.0)
cao = ContextualAmbientOcclusion(Input=lao, DepthMaps=maps)
cao.PoseTransform.Translate = [32.0, 30.0, 36.0]
cao.Backend = "CPU"
cao_path = os.path.join(outdir, "hydrogen-cao.pvti")
SaveData(cao_path, proxy=cao, PointDataArrays=["AmbientOcclusion", "ClipCategory"], DataMode="Binary")
wait_for_pieces("hydrogen-cao")

from vtkmodules.vtkIOXML import vtkXMLPImageDataReader, vtkXMLImageDataReader  # noqa: E402

import contextualao  # noqa: E402

pieces = vtkXMLPImageDataReader()
pieces.SetFileName(path)
pieces.Update()
whole = pieces.GetOutput().GetNumberOfPoints()
sizes = []
for i in range(pieces.GetNumberOfPieces()):
    name = os.path.join(outdir, "hydrogen-lao", "hydrogen-lao_%d.vti" % i)
    if os.path.exists(name):
        r = vtkXMLImageDataReader()
        r.SetFileName(name)
        r.Update()
        sizes.append(r.GetOutput().GetNumberOfPoints())
print("ranks %d, pieces %d, piece sizes %s of %d voxels" % (ranks, pieces.GetNumberOfPieces(), sizes, whole))
check(ranks == 2, "two MPI ranks")
check(pieces.GetNumberOfPieces() == ranks and len(sizes) == ranks and all(0 < s < whole for s in sizes),
      "the volume was split into one piece per rank")

serial_reader = vtkXMLImageDataReader()
serial_reader.SetFileName(os.path.join(data, "hydrogen.vti"))
serial = contextualao.vtkLocalAmbientOcclusion()
serial.SetInputConnection(serial_reader.GetOutputPort())
serial.SetQualityToCustom()
serial.SetRayPattern(serial.RAYS_26)
serial.SetBackendToCPU()
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction  # noqa: E402
serial_opacity = vtkPiecewiseFunction()
serial_opacity.AddPoint(0.0, 0.0)
serial_opacity.AddPoint(0.05, 0.1)
serial_opacity.AddPoint(0.4, 0.9)
serial.SetOpacityFunction(serial_opacity)
serial.Update()
a = pieces.GetOutput().GetPointData().GetArray("AmbientOcclusion")
b = serial.GetOutput().GetPointData().GetArray("AmbientOcclusion")
check(a is not None and b is not None and a.GetNumberOfTuples() == b.GetNumberOfTuples(),
      "the merged pieces cover the volume")
if a is not None and b is not None:
    differing = sum(1 for i in range(b.GetNumberOfTuples()) if a.GetValue(i) != b.GetValue(i))
    check(differing == 0, "distributed LAO == serial LAO at every voxel (%d of %d differ)"
          % (differing, b.GetNumberOfTuples()))
# A reader that cannot produce sub-extents (MetaImage): each rank reads the
# whole volume, and the output is still distributed and equal to serial.
mr = OpenDataFile(os.path.join(data, "HeadMRVolume.mhd"))
mr_lao = LocalAmbientOcclusion(Input=mr)
mr_lao.Backend = "CPU"
mr_path = os.path.join(outdir, "headmr-lao.pvti")
SaveData(mr_path, proxy=mr_lao, PointDataArrays=["AmbientOcclusion"], DataMode="Binary")
wait_for_pieces("headmr-lao")
from vtkmodules.vtkIOImage import vtkMetaImageReader  # noqa: E402
mr_pieces = vtkXMLPImageDataReader()
mr_pieces.SetFileName(mr_path)
mr_pieces.Update()
mr_reader = vtkMetaImageReader()
mr_reader.SetFileName(os.path.join(data, "HeadMRVolume.mhd"))
mr_serial = contextualao.vtkLocalAmbientOcclusion()
mr_serial.SetInputConnection(mr_reader.GetOutputPort())
mr_serial.SetBackendToCPU()
mr_serial.Update()
a = mr_pieces.GetOutput().GetPointData().GetArray("AmbientOcclusion")
b = mr_serial.GetOutput().GetPointData().GetArray("AmbientOcclusion")
ok = a is not None and b is not None and a.GetNumberOfTuples() == b.GetNumberOfTuples()
differing = sum(1 for i in range(b.GetNumberOfTuples()) if a.GetValue(i) != b.GetValue(i)) if ok else -1
check(ok and differing == 0 and mr_pieces.GetNumberOfPieces() == ranks,
      "HeadMR (a reader without sub-extents): distributed LAO == serial (%d differ)" % differing)

# CAO: the same comparison.
from vtkmodules.vtkFiltersSources import vtkSphereSource  # noqa: E402
from vtkmodules.vtkCommonTransforms import vtkTransform  # noqa: E402
cao_pieces = vtkXMLPImageDataReader()
cao_pieces.SetFileName(cao_path)
cao_pieces.Update()
s = vtkSphereSource()
s.SetRadius(14.0)
s.SetThetaResolution(32)
s.SetPhiResolution(16)
v_maps = contextualao.vtkClipDepthMaps()
v_maps.SetInputConnection(s.GetOutputPort())
v_maps.SetReach(8.0)
v_cao = contextualao.vtkContextualAmbientOcclusion()
v_cao.SetInputConnection(serial.GetOutputPort())
v_cao.SetDepthMapsConnection(v_maps.GetOutputPort())
t = vtkTransform()
t.Translate(32.0, 30.0, 36.0)
v_cao.SetPoseTransform(t)
v_cao.SetBackendToCPU()
v_cao.Update()
for name in ("AmbientOcclusion", "ClipCategory"):
    a = cao_pieces.GetOutput().GetPointData().GetArray(name)
    b = v_cao.GetOutput().GetPointData().GetArray(name)
    ok = a is not None and b is not None and a.GetNumberOfTuples() == b.GetNumberOfTuples()
    differing = sum(1 for i in range(b.GetNumberOfTuples()) if a.GetValue(i) != b.GetValue(i)) if ok else -1
    check(ok and differing == 0, "distributed CAO %s == serial at every voxel (%d differ)" % (name, differing))
check(v_cao.GetOutput().GetPointData().GetArray("ClipCategory").GetRange() == (0.0, 2.0),
      "the pose clips, affects and leaves voxels")
finish()

"""The CPU contextual update builds on the previous pose (cao::ContextualUpdate):
one vtkContextualAmbientOcclusion driven along a path must give, at every
pose, bit for bit what a new filter gives for that pose alone, while
classifying only the union of the two poses' candidate boxes.

The path mixes what can go wrong with state kept between poses: small
moves (boxes overlap), a jump (disjoint boxes), a pose outside the volume
(empty box), a rotation with a scale, a change of mode and back, a change
of anti-aliasing samples, other depth maps (another mesh), and a new
opacity upstream (the LAO re-executes: the kept state must be dropped).

The kept arrays are reused in place only while nothing else holds them: an
array held from an earlier output keeps its values (and a released one is
reused, which shows the copy is due to the holder).

Negative controls: the output at pose k differs from a new filter's at pose
k+1 (so the comparison sees a pose), the small moves classify fewer
voxels than the volume has (so the region logic is exercised), and bricks
decide voxels at every pose inside the volume (so the brick path is).

AOFormat UNORM16 along the same path: the float AO quantized, exact against
the quantized full recompute (negative control: truncation differs).

At every pose, the classification that decides provably uniform bricks at
once (cao::ClipMapsTiles) and voxels from their centre (the proof maps of
cao::ProofMaps) equals testing every
voxel sample by sample (CAO_CLASSIFY_PER_SAMPLE=1, which decides nothing by
brick or centre: checked), bit for bit."""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkCommonTransforms import vtkTransform
from vtkmodules.vtkFiltersSources import vtkCubeSource, vtkSphereSource
from vtkmodules.vtkIOImage import vtkSLCReader

from contextualao import (vtkClipDepthMaps, vtkContextualAmbientOcclusion,
                          vtkLocalAmbientOcclusion as LAO)

data = os.environ.get("CAO_DATA_DIR", "Data")
failures = []


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


reader = vtkSLCReader()
reader.SetFileName(os.path.join(data, "neghip.slc"))
reader.Update()
voxels = reader.GetOutput().GetNumberOfPoints()
tf = vtkPiecewiseFunction()
tf.AddPoint(0, 0.0)
tf.AddPoint(40, 0.0)
tf.AddPoint(255, 0.8)
lao = LAO()
lao.SetInputConnection(reader.GetOutputPort())
lao.SetOpacityFunction(tf)
lao.SetReach(4.0)
lao.SetQualityToCustom()  # the settings below apply
lao.SetRayPattern(LAO.RAYS_14)
lao.SetBackendToCPU()
lao.OutputOpacityOn()

sphere = vtkSphereSource()
sphere.SetRadius(10)
sphere.SetThetaResolution(24)
sphere.SetPhiResolution(24)
cube = vtkCubeSource()
cube.SetXLength(14)
cube.SetYLength(9)
cube.SetZLength(20)
maps = {}
for name, source in (("sphere", sphere), ("cube", cube)):
    m = vtkClipDepthMaps()
    m.SetInputConnection(source.GetOutputPort())
    m.SetReach(4.0)
    m.SetPoseScaleRange(0.5, 2.0)
    m.Update()
    maps[name] = m

ARRAYS = ("AmbientOcclusion", "ClippedOpacity", "ClipCategory")


def configure(f, mesh, mode, aa, matrix):
    f.SetInputConnection(0, lao.GetOutputPort())
    f.SetInputConnection(1, maps[mesh].GetOutputPort())
    f.SetBackendToCPU()
    f.SetMode(mode)
    f.SetAntiAliasingSamples(aa)
    t = vtkTransform()
    t.SetMatrix(matrix)
    f.SetPoseTransform(t)


def arrays(image):
    out = {}
    for name in ARRAYS:
        a = vtk_to_numpy(image.GetPointData().GetArray(name))
        out[name] = a.view(np.uint32 if a.dtype == np.float32 else a.dtype).copy()
    return out


def field(image, name, c):
    return image.GetFieldData().GetArray(name).GetComponent(0, c)


def fresh(mesh, mode, aa, matrix, per_sample=False):
    f = vtkContextualAmbientOcclusion()
    configure(f, mesh, mode, aa, matrix)
    if per_sample:
        os.environ["CAO_CLASSIFY_PER_SAMPLE"] = "1"
    f.Update()
    os.environ.pop("CAO_CLASSIFY_PER_SAMPLE", None)
    return f.GetOutput()


def pose(tx, ty, tz, rz=0.0, s=1.0):
    t = vtkTransform()
    t.Translate(tx, ty, tz)
    t.RotateZ(rz)
    t.Scale(s, s, s)
    return t.GetMatrix()


SUB, PROBE = vtkContextualAmbientOcclusion.SUBTRACTION, vtkContextualAmbientOcclusion.PROBING
path = [("first pose", "sphere", SUB, 16, pose(30, 34, 33)),
        ("small move", "sphere", SUB, 16, pose(32, 35, 33)),
        ("small move", "sphere", SUB, 16, pose(34, 35, 34)),
        ("jump (disjoint boxes)", "sphere", SUB, 16, pose(12, 14, 12)),
        ("outside the volume (empty box)", "sphere", SUB, 16, pose(400, 0, 0)),
        ("back in", "sphere", SUB, 16, pose(34, 35, 34)),
        ("rotation and scale 1.3", "sphere", SUB, 16, pose(34, 36, 34, 30, 1.3)),
        ("probing", "sphere", PROBE, 16, pose(34, 36, 34, 30, 1.3)),
        ("probing, small move", "sphere", PROBE, 16, pose(35, 36, 34, 30, 1.3)),
        ("subtraction again", "sphere", SUB, 16, pose(35, 36, 34, 30, 1.3)),
        ("4 anti-aliasing samples", "sphere", SUB, 4, pose(35, 36, 34, 30, 1.3)),
        ("other maps (a cube)", "cube", SUB, 4, pose(33, 36, 30, 10)),
        ("cube, small move", "cube", SUB, 4, pose(34, 36, 30, 12))]

kept = vtkContextualAmbientOcclusion()
previous = None
small_regions = []
small_unchanged = []
bricks_used = []
centres_used = []
for i, (what, mesh, mode, aa, matrix) in enumerate(path):
    configure(kept, mesh, mode, aa, matrix)
    kept.Update()
    got = kept.GetOutput()
    want = fresh(mesh, mode, aa, matrix)
    a, b = arrays(got), arrays(want)
    same = all(np.array_equal(a[n], b[n]) for n in ARRAYS)
    counts = [field(got, "CategoryCounts", c) for c in range(3)]
    same_counts = counts == [field(want, "CategoryCounts", c) for c in range(3)]
    classified = field(got, "UpdateRegion", 0)
    check(same and same_counts,
          "pose %d (%s): the kept filter equals a new one bit for bit (counts %s, %d of %d "
          "voxels classified)" % (i, what, counts, classified, voxels))
    if what.startswith("small move") or what == "cube, small move":
        small_regions.append(classified)
        small_unchanged.append(field(got, "UpdateRegion", 4))
    # Bricks proven uniform (cao::ClipMapsTiles) against every voxel tested
    # sample by sample: the same bits.
    slow_image = fresh(mesh, mode, aa, matrix, per_sample=True)
    slow = arrays(slow_image)
    # The per-sample run really tested every voxel sample by sample.
    check(field(slow_image, "UpdateRegion", 2) == 0,
          "pose %d: CAO_CLASSIFY_PER_SAMPLE=1 decided no voxel by brick (%d)"
          % (i, field(slow_image, "UpdateRegion", 2)))
    check(field(slow_image, "UpdateRegion", 5) == 0,
          "pose %d: CAO_CLASSIFY_PER_SAMPLE=1 decided no voxel from its centre (%d)"
          % (i, field(slow_image, "UpdateRegion", 5)))
    by_brick = field(got, "UpdateRegion", 2)
    by_centre = field(got, "UpdateRegion", 5)
    check(all(np.array_equal(a[n], slow[n]) for n in ARRAYS),
          "pose %d: deciding %d voxels by brick and %d from their centre (proof maps) gives "
          "the bits of testing every sample" % (i, by_brick, by_centre))
    bricks_used.append(by_brick)
    centres_used.append(by_centre)
    if previous is not None:
        # Negative control: the previous pose's output is not this pose's.
        differs = any(not np.array_equal(previous[n], b[n]) for n in ARRAYS)
        check(differs, "pose %d: the previous pose's output differs from this pose's "
              "(the comparison sees the pose)" % i)
    previous = a
check(sum(1 for b in bricks_used if b > 0) >= len(path) - 1,
      "bricks decide voxels at the poses inside the volume: %s" % [int(b) for b in bricks_used])
check(sum(1 for c in centres_used if c > 0) >= len(path) - 2,
      "the proof maps decide voxels from their centre at the poses inside the volume: %s"
      % [int(c) for c in centres_used])
check(field(fresh(*path[0][1:]), "UpdateRegion", 0) == voxels,
      "a new filter classifies the whole volume (%d voxels)" % voxels)
check(small_regions and max(small_regions) < voxels / 2,
      "small moves write only this pose's box and the previous box's bricks that "
      "held a clipped state: %s of %d voxels" % ([int(r) for r in small_regions], voxels))
check(small_unchanged and min(small_unchanged) > 0,
      "small moves leave bricks that keep their category unwritten: %s voxels"
      % [int(u) for u in small_unchanged])

# A new opacity upstream: the LAO re-executes, the kept state is dropped.
tf.AddPoint(120, 0.5)
kept.Update()
want = fresh(*path[-1][1:])
a, b = arrays(kept.GetOutput()), arrays(want)
check(all(np.array_equal(a[n], b[n]) for n in ARRAYS) and
      field(kept.GetOutput(), "UpdateRegion", 0) == voxels,
      "after a new opacity the kept filter starts over and equals a new one")

# An array held from an earlier output keeps its values; a released one is
# reused in place.
held = kept.GetOutput().GetPointData().GetArray("AmbientOcclusion")
held_values = vtk_to_numpy(held).copy()
configure(kept, "cube", SUB, 4, pose(36, 36, 31, 14))
kept.Update()
now = kept.GetOutput().GetPointData().GetArray("AmbientOcclusion")
check(np.array_equal(vtk_to_numpy(held), held_values) and
      not np.array_equal(vtk_to_numpy(now), held_values),
      "a held AO array keeps its values when the next pose is computed")
address = now.GetAddressAsString("vtkFloatArray")
del now, held
configure(kept, "cube", SUB, 4, pose(37, 36, 31, 14))
kept.Update()
check(kept.GetOutput().GetPointData().GetArray("AmbientOcclusion").GetAddressAsString(
    "vtkFloatArray") == address, "an AO array nobody holds is reused in place")
# The arrays written in place do not keep a range cached before: the
# categories' range at this pose (some clipped), then at a pose outside the
# volume (all unaffected) in the same array.
categories = kept.GetOutput().GetPointData().GetArray("ClipCategory")
before_range = categories.GetRange()  # (a range asked for is cached in the array)
category_address = categories.GetAddressAsString("vtkUnsignedCharArray")
del categories
configure(kept, "cube", SUB, 4, pose(400, 0, 0))
kept.Update()
categories = kept.GetOutput().GetPointData().GetArray("ClipCategory")
check(before_range[0] == 0 and categories.GetAddressAsString("vtkUnsignedCharArray") == category_address
      and categories.GetRange() == (2.0, 2.0),
      "the categories written in place report this pose's range (2, 2), not the cached %s: %s"
      % (before_range, categories.GetRange()))
del categories

# Verify (a full recompute) after the kept path: exact.
kept.VerifyOn()
kept.Update()
v = kept.GetOutput().GetFieldData().GetArray("Verification")
check(v is not None and v.GetComponent(0, 1) == 0, "Verify after the path: no voxel differs")

# AOFormat UNORM16: the AO kept and output as 16-bit unsigned normalised, as
# the GPU stores it. Along the path, a kept UNORM16 filter gives at every
# pose the float filter's AO quantized (q = f * 65535 + 0.5 in float,
# truncated) and the same clipped opacity and categories; its Verify
# compares with the full recompute quantized the same way.
def quantize(f):
    return (f * np.float32(65535) + np.float32(0.5)).astype(np.uint16)


kept16 = vtkContextualAmbientOcclusion()
kept16.SetAOFormat(vtkContextualAmbientOcclusion.UNORM16)
kept16.VerifyOn()
rounding_seen = False
for i, (what, mesh, mode, aa, matrix) in enumerate(path[:7]):
    configure(kept16, mesh, mode, aa, matrix)
    kept16.Update()
    got = kept16.GetOutput()
    ao16 = got.GetPointData().GetArray("AmbientOcclusion")
    want = fresh(mesh, mode, aa, matrix)
    f = vtk_to_numpy(want.GetPointData().GetArray("AmbientOcclusion"))
    q = vtk_to_numpy(ao16)
    others = all(np.array_equal(arrays(got)[n], arrays(want)[n]) for n in ARRAYS[1:])
    check(ao16.GetDataTypeAsString() == "unsigned short" and np.array_equal(q, quantize(f)) and others,
          "UNORM16 pose %d (%s): the float AO quantized, the same clipped opacity and categories"
          % (i, what))
    check(got.GetFieldData().GetArray("Verification").GetComponent(0, 1) == 0,
          "UNORM16 pose %d: Verify finds no voxel that differs from the quantized full LAO" % i)
    setup = field(got, "StageMilliseconds", 4)
    check((setup > 0) if i == 0 else (what != "small move" or setup == 0),
          "UNORM16 pose %d (%s): the setup (%.2f ms) is paid at the first pose, not at small moves"
          % (i, what, setup))
    # Negative control: truncating instead of rounding differs somewhere, so
    # the comparison sees the quantization's rounding.
    rounding_seen = rounding_seen or not np.array_equal(q, (f * np.float32(65535)).astype(np.uint16))
check(rounding_seen, "truncating the float AO instead of rounding it gives other values")
# A format change drops the kept state: the next pose starts over.
kept16.SetAOFormat(vtkContextualAmbientOcclusion.FLOAT)
kept16.Update()
out = kept16.GetOutput()
check(out.GetPointData().GetArray("AmbientOcclusion").GetDataTypeAsString() == "float" and
      field(out, "UpdateRegion", 0) == voxels and
      np.array_equal(arrays(out)["AmbientOcclusion"], arrays(fresh(*path[6][1:]))["AmbientOcclusion"]),
      "back to FLOAT: the whole volume is written again and equals a new filter")
# An AOFormat out of range is an error that names the values.
from vtkmodules.vtkCommonCore import vtkCommand
errors = []
bad = vtkContextualAmbientOcclusion()
configure(bad, *path[0][1:])
bad.SetAOFormat(7)
bad.AddObserver(vtkCommand.ErrorEvent, lambda o, e: errors.append(e))
bad.GetExecutive().AddObserver(vtkCommand.ErrorEvent, lambda o, e: errors.append(e))
bad.Update()
check(len(errors) > 0 and bad.GetOutput().GetPointData().GetArray("AmbientOcclusion") is None,
      "AOFormat 7 is refused with an error, and nothing is output")

if failures:
    print("%d check(s) failed" % len(failures))
    sys.exit(1)

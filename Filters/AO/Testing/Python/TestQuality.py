"""Quality levels (Low, Medium, High, Custom: cao::Quality), start offsets and ray variations, end to end through the
VTK filters (CPU backend, small reach so it runs in seconds):

 - for each quality level, vtkLocalAmbientOcclusion with Quality=P gives
   bit for bit the AO of the same filter with the level's settings set by
   hand (read back from the LAOSettings field array, which records the
   settings in effect), and differs from the CUSTOM defaults;
 - changing Quality re-executes the filter, setting it again does not;
 - vtkContextualAmbientOcclusion downstream of an LAO with RayVariation
   ROTATE_JITTER and StartOffset 0.5 rebuilds the same plan from
   LAOSettings: its Verify (a full recompute) finds no difference at any
   pose; with the variation stripped from the array (an old 8-component
   array) the same check does find differences, so it is not vacuous; the
   CAO filter's own LAO (no upstream) honours a forwarded quality;
 - a piece of an LAO with RayVariation ROTATE whose input starts at odd
   indices equals the whole volume's values at those voxels (the variant
   follows the global voxel index)."""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkOutputWindow, vtkStringOutputWindow
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPiecewiseFunction
from vtkmodules.vtkCommonTransforms import vtkTransform
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkIOImage import vtkMetaImageReader, vtkSLCReader
from vtkmodules.vtkIOXML import vtkXMLImageDataReader

from contextualao import (vtkClipDepthMaps, vtkContextualAmbientOcclusion,
                          vtkLocalAmbientOcclusion as LAO)

data = os.environ.get("CAO_DATA_DIR", "Data")
failures = []


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


def ao_of(image):
    return vtk_to_numpy(image.GetPointData().GetArray("AmbientOcclusion")).copy()


def parameters(image):
    """LAOSettings as a dict of component name -> value."""
    a = image.GetFieldData().GetArray("LAOSettings")
    return {a.GetComponentName(c): a.GetComponent(0, c) for c in range(a.GetNumberOfComponents())}


# HeadMR: 48 x 62 x 42 voxels of spacing 4; a reach of 4 voxels.
head = vtkMetaImageReader()
head.SetFileName(os.path.join(data, "HeadMRVolume.mhd"))
head.Update()
volume = head.GetOutput()
tf = vtkPiecewiseFunction()
tf.AddPoint(0, 0.0)
tf.AddPoint(40, 0.0)
tf.AddPoint(90, 0.4)
tf.AddPoint(255, 0.9)
REACH = 16.0


def lao_filter(**settings):
    f = LAO()
    f.SetInputData(volume)
    f.SetOpacityFunction(tf)
    f.SetReach(REACH)
    f.SetBackendToCPU()
    f.SetQualityToCustom()  # the individual settings apply (unless given a quality level)
    for name, value in settings.items():
        getattr(f, "Set" + name)(value)
    return f


# Defaults of the new properties; out-of-range values are kept as given and
# make the update fail with an error that states the limit (they used to be
# clamped, or, for the reach, silently replaced by the default).
f = LAO()
check((f.GetRayPattern(), f.GetSampleDensity(), f.GetStartOffset(), f.GetRayVariation(),
       f.GetQuality())
      == (LAO.RAYS_14, 1.0, 0.5, LAO.NONE, LAO.LOW),
      "defaults: Low quality, the individual settings equal to its (14 rays, density 1, "
      "offset 0.5, no variation)")
errors = []
for name, value, limit in (("StartOffset", 1.5, "[0, 1)"), ("SampleDensity", -1.0, "0.001 to 1000"),
                           ("RayVariation", 7, "unknown ray variation"),
                           ("Quality", 9, "(High); got 9"),
                           ("Reach", -1.0, "0 selects the default"),
                           ("Reach", float("nan"), "0 selects the default"),
                           ("NumberOfSamples", 1000000000, "2 to 65536"),
                           ("NumberOfSamples", 1, "one sees no occluder"),
                           ("RayPattern", 99, "unknown ray pattern"),
                           ("ScalarOpacityUnitDistance", 0.0, "positive and finite")):
    g = lao_filter(**{name: value})
    got = getattr(g, "Get" + name)()
    kept = got == value or (value != value and got != got)
    window = vtkStringOutputWindow()  # the filter's error text, as VTK prints it
    vtkOutputWindow.SetInstance(window)
    g.Update()
    vtkOutputWindow.SetInstance(None)
    text = window.GetOutput()
    check(kept and limit in text and g.GetOutput().GetPointData().GetArray("AmbientOcclusion") is None,
          "%s = %r is kept and is an error stating the limit (%r)" % (name, value, limit))
f.SetRayVariationToRotate()
f.SetQualityToMedium()
check((f.GetRayVariation(), f.GetQuality()) == (LAO.ROTATE, LAO.MEDIUM),
      "SetRayVariationTo... and SetQualityTo...")

# The defaults before Low quality: 26 rays, one sample per voxel.
custom = lao_filter(RayPattern=LAO.RAYS_26, SampleDensity=1.0, RayVariation=LAO.NONE)
custom.Update()
custom_ao = ao_of(custom.GetOutput())
p = parameters(custom.GetOutput())
# One component per setting, named as the setting (its Set method and the
# ParaView property), then what the run made of them.
SETTING_NAMES = ["RayPattern", "NumberOfRays", "Reach", "NumberOfSamples", "SampleDensity",
                 "StartOffset", "RayVariation", "Quality", "Rays", "Step",
                 "ScalarOpacityUnitDistance", "Milliseconds"]
check(list(p) == SETTING_NAMES
      and (p["RayPattern"], p["StartOffset"], p["RayVariation"], p["Quality"], p["Reach"])
      == (LAO.RAYS_26, 0.5, LAO.NONE, LAO.CUSTOM, REACH),
      "LAOSettings names every setting, the custom settings in effect: %s" % p)

# The default filter is Low quality, bit for bit, and equal to
# Custom with the individual defaults.
default = LAO()
default.SetInputData(volume)
default.SetOpacityFunction(tf)
default.SetReach(REACH)
default.SetBackendToCPU()
default.Update()
low = lao_filter(Quality=LAO.LOW)
low.Update()
custom_defaults = lao_filter()
custom_defaults.Update()
check(parameters(default.GetOutput())["Quality"] == LAO.LOW
      and np.array_equal(ao_of(default.GetOutput()), ao_of(low.GetOutput()))
      and np.array_equal(ao_of(default.GetOutput()), ao_of(custom_defaults.GetOutput())),
      "the default is Low quality, equal to Custom with the individual defaults")
# A setting the default quality overrides is named in a warning.
default.SetRayPattern(LAO.RAYS_26)
window = vtkStringOutputWindow()
vtkOutputWindow.SetInstance(window)
default.Update()
vtkOutputWindow.SetInstance(None)
check("Quality low overrides RayPattern 2" in window.GetOutput()
      and "Custom (0)" in window.GetOutput(),
      "a ray pattern set under the default quality is reported as overridden: %r"
      % " ".join(window.GetOutput().split())[:200])
check(np.array_equal(ao_of(default.GetOutput()), ao_of(low.GetOutput())),
      "... and does not change the AO")
# Negative control: another quality level over settings left at their defaults
# (what ParaView pushes) warns of nothing.
quiet = LAO()
quiet.SetInputData(volume)
quiet.SetOpacityFunction(tf)
quiet.SetReach(REACH)
quiet.SetBackendToCPU()
quiet.SetQualityToMedium()
window = vtkStringOutputWindow()
vtkOutputWindow.SetInstance(window)
quiet.Update()
vtkOutputWindow.SetInstance(None)
check("overrides" not in window.GetOutput(),
      "a quality level over default settings warns of nothing: %r" % window.GetOutput()[:200])

# Each quality level equals its own settings set by hand, and is not the old default.
for level, name in ((LAO.LOW, "low"), (LAO.MEDIUM, "medium"),
                     (LAO.HIGH, "high")):
    # NumberOfSamples and the other individual settings are ignored under a quality level.
    f = lao_filter(Quality=level, NumberOfSamples=3, StartOffset=0.25,
                   RayVariation=LAO.JITTER, SampleDensity=3.0)
    f.Update()
    got = ao_of(f.GetOutput())
    p = parameters(f.GetOutput())
    check(p["Quality"] == level and p["Reach"] == REACH,
          "%s: LAOSettings records the quality and the user's reach" % name)
    by_hand = lao_filter(RayPattern=int(p["RayPattern"]), NumberOfRays=int(p["NumberOfRays"]),
                         NumberOfSamples=int(p["NumberOfSamples"]), StartOffset=p["StartOffset"],
                         RayVariation=int(p["RayVariation"]))
    by_hand.Update()
    q = parameters(by_hand.GetOutput())
    keys = ("RayPattern", "Rays", "NumberOfSamples", "Step", "NumberOfRays", "StartOffset",
            "RayVariation")
    same = {k: q[k] for k in keys} == {k: p[k] for k in keys}
    check(same and np.array_equal(got, ao_of(by_hand.GetOutput())),
          "%s: bit-identical to its settings by hand (pattern %d, %d rays, %d samples, offset %g, "
          "variation %d)" % (name, p["RayPattern"], p["Rays"], p["NumberOfSamples"], p["StartOffset"],
                             p["RayVariation"]))
    check(not np.array_equal(got, custom_ao), "%s: differs from 26 rays at one sample per voxel" % name)

# Re-execution: a new quality re-executes the filter, the same one does not.
runs = [0]
f = lao_filter(RayPattern=LAO.RAYS_26, SampleDensity=1.0, RayVariation=LAO.NONE)
f.AddObserver("StartEvent", lambda *_: runs.__setitem__(0, runs[0] + 1))
f.Update()
f.SetQuality(LAO.LOW)
f.Update()
low = ao_of(f.GetOutput())
f.SetQuality(LAO.LOW)
f.Update()
check(runs[0] == 2, "a quality level change re-executes the LAO, the same level again does not (%d runs)"
      % runs[0])
f.SetQualityToCustom()
f.Update()
check(runs[0] == 3 and np.array_equal(ao_of(f.GetOutput()), custom_ao)
      and not np.array_equal(low, custom_ao), "back to custom: the custom AO again")

# The contextual update stays exact with a variation and a start offset.
neghip = vtkSLCReader()
neghip.SetFileName(os.path.join(data, "neghip.slc"))
ntf = vtkPiecewiseFunction()
ntf.AddPoint(0, 0.0)
ntf.AddPoint(40, 0.0)
ntf.AddPoint(255, 0.8)
lao = LAO()
lao.SetInputConnection(neghip.GetOutputPort())
lao.SetOpacityFunction(ntf)
lao.SetReach(4.0)
lao.SetRayPattern(LAO.RAYS_14)
lao.SetRayVariation(LAO.ROTATE_JITTER)
lao.SetStartOffset(0.5)
lao.SetBackendToCPU()
sphere = vtkSphereSource()
sphere.SetRadius(12)
sphere.SetThetaResolution(32)
sphere.SetPhiResolution(32)
maps = vtkClipDepthMaps()
maps.SetInputConnection(sphere.GetOutputPort())
maps.SetReach(4.0)
cao = vtkContextualAmbientOcclusion()
cao.SetInputConnection(0, lao.GetOutputPort())
cao.SetInputConnection(1, maps.GetOutputPort())
cao.SetBackendToCPU()
cao.VerifyOn()
pose = vtkTransform()
pose.Translate(20, 30, 33)
cao.SetPoseTransform(pose)
worst, affected = 0.0, 0
for step in range(3):
    pose.Translate(4, 1, 0)
    cao.Update()
    v = cao.GetOutput().GetFieldData().GetArray("Verification")
    worst = max(worst, v.GetComponent(0, 0), v.GetComponent(0, 1))
    affected += cao.GetOutput().GetFieldData().GetArray("CategoryCounts").GetComponent(0, 1)
check(worst == 0.0 and affected > 0, "CAO after an LAO with ROTATE_JITTER and offset 0.5 equals "
      "the full recompute at 3 poses (%d affected voxels)" % affected)



def legacy_parameters(image):
    """The predecessor of LAOSettings, as outputs before the start offset
    and the variation wrote it: "LAOParameters", 8 components by position
    (RayPattern, Rays, Samples, Reach, Step, UnitDistance, FibonacciRays,
    Milliseconds)."""
    p = parameters(image)
    old = vtkDoubleArray()
    old.SetName("LAOParameters")
    old.SetNumberOfComponents(8)
    old.InsertNextTuple([p[k] for k in ("RayPattern", "Rays", "NumberOfSamples", "Reach", "Step",
                                        "ScalarOpacityUnitDistance", "NumberOfRays",
                                        "Milliseconds")])
    return old


# The same LAO output with the variation and offset stripped (an old
# 8-component LAOParameters instead of LAOSettings): the CAO filter then
# rebuilds a plan without them, and its verification sees the difference.
legacy = vtkImageData()
legacy.ShallowCopy(lao.GetOutput())
legacy.GetFieldData().RemoveArray("LAOSettings")
legacy.GetFieldData().AddArray(legacy_parameters(lao.GetOutput()))
cao_legacy = vtkContextualAmbientOcclusion()
cao_legacy.SetInputData(0, legacy)
cao_legacy.SetInputConnection(1, maps.GetOutputPort())
cao_legacy.SetBackendToCPU()
cao_legacy.VerifyOn()
cao_legacy.SetPoseTransform(pose)
cao_legacy.Update()
v = cao_legacy.GetOutput().GetFieldData().GetArray("Verification")
check(v is not None and v.GetComponent(0, 1) > 0,
      "an 8-component LAOParameters is read with the defaults (the stripped variation shows: "
      "%s differing voxels)" % (v.GetComponent(0, 1) if v else None))
# An 8-component array of an LAO without offset or variation is still exact.
plain = LAO()
plain.SetQualityToCustom()
plain.SetSampleDensity(1.0)
plain.SetRayVariationToNone()
plain.SetInputConnection(neghip.GetOutputPort())
plain.SetOpacityFunction(ntf)
plain.SetReach(4.0)
plain.SetRayPattern(LAO.RAYS_14)
plain.SetStartOffset(0.0)  # as every LAO did before the offset existed
plain.SetBackendToCPU()
plain.Update()
legacy.ShallowCopy(plain.GetOutput())
legacy.GetFieldData().RemoveArray("LAOSettings")
legacy.GetFieldData().AddArray(legacy_parameters(plain.GetOutput()))
cao_legacy.SetInputData(0, legacy)
cao_legacy.Update()
v = cao_legacy.GetOutput().GetFieldData().GetArray("Verification")
check(v is not None and v.GetComponent(0, 0) == 0.0 and
      cao_legacy.GetOutput().GetFieldData().GetArray("CategoryCounts").GetComponent(0, 1) > 0,
      "an 8-component LAOParameters without variation: CAO exact")

# An LAO written before the quality levels were one vocabulary names its
# level "QualityPreset": still read, the CAO over it exact (the settings
# travel in the other components).
old_named = vtkImageData()
old_named.ShallowCopy(lao.GetOutput())
renamed = vtkDoubleArray()
renamed.DeepCopy(lao.GetOutput().GetFieldData().GetArray("LAOSettings"))
for c in range(renamed.GetNumberOfComponents()):
    if renamed.GetComponentName(c) == "Quality":
        renamed.SetComponentName(c, "QualityPreset")
old_named.GetFieldData().RemoveArray("LAOSettings")
old_named.GetFieldData().AddArray(renamed)
cao_old = vtkContextualAmbientOcclusion()
cao_old.SetInputData(0, old_named)
cao_old.SetInputConnection(1, maps.GetOutputPort())
cao_old.SetBackendToCPU()
cao_old.VerifyOn()
cao_old.SetPoseTransform(pose)
cao_old.Update()
v = cao_old.GetOutput().GetFieldData().GetArray("Verification")
check(v is not None and v.GetComponent(0, 0) == 0.0 and v.GetComponent(0, 1) == 0,
      "an LAOSettings with the former component name QualityPreset: CAO exact")

# The CAO filter's own LAO (no upstream LAO) takes the forwarded settings.
direct = vtkContextualAmbientOcclusion()
direct.SetInputConnection(0, neghip.GetOutputPort())
direct.SetInputConnection(1, maps.GetOutputPort())
direct.SetOpacityFunction(ntf)
direct.SetReach(4.0)
direct.SetQualityToMedium()  # (the LAO filter's levels, by name)
direct.SetBackendToCPU()
direct.VerifyOn()
direct.SetPoseTransform(pose)
direct.Update()
p = parameters(direct.GetOutput())
ref = LAO()
ref.SetInputConnection(neghip.GetOutputPort())
ref.SetOpacityFunction(ntf)
ref.SetReach(4.0)
ref.SetQuality(LAO.MEDIUM)
ref.SetBackendToCPU()
ref.Update()
v = direct.GetOutput().GetFieldData().GetArray("Verification")
check(p == {**parameters(ref.GetOutput()), "Milliseconds": p["Milliseconds"]}
      and v.GetComponent(0, 0) == 0.0,
      "the CAO filter's internal LAO follows a forwarded Quality, exactly")
named = []
for setter, level in (("SetQualityToLow", LAO.LOW), ("SetQualityToHigh", LAO.HIGH),
                      ("SetQualityToCustom", LAO.CUSTOM), ("SetQualityToMedium", LAO.MEDIUM)):
    getattr(direct, setter)()
    named.append(direct.GetQuality() == level)
check(all(named), "the CAO filter names the levels as the LAO filter does: %s" % named)
direct.SetStartOffset(0.5)  # overridden by the quality: the settings in effect are unchanged
direct.SetQuality(LAO.CUSTOM)
direct.SetRayVariation(LAO.ROTATE)
direct.Update()
p = parameters(direct.GetOutput())
check((direct.GetStartOffset(), direct.GetRayVariation(), direct.GetSampleDensity()) ==
      (0.5, LAO.ROTATE, 1.0) and (p["StartOffset"], p["RayVariation"], p["Quality"]) ==
      (0.5, LAO.ROTATE, LAO.CUSTOM) and direct.GetPrecomputeCount() == 2,
      "forwarded StartOffset and RayVariation reach the internal LAO")

# A piece whose input starts at odd global indices equals the whole volume.
def hydrogen_lao():
    reader = vtkXMLImageDataReader()
    reader.SetFileName(os.path.join(data, "hydrogen.vti"))
    htf = vtkPiecewiseFunction()
    htf.AddPoint(0.0, 0.0)
    htf.AddPoint(0.05, 0.1)
    htf.AddPoint(0.4, 0.9)
    f = LAO()
    f.SetQualityToCustom()
    f.SetInputConnection(reader.GetOutputPort())
    f.SetOpacityFunction(htf)
    f.SetReach(4.0)
    f.SetRayPattern(LAO.RAYS_6)
    f.SetRayVariationToRotate()
    f.SetBackendToCPU()
    return reader, f, htf


_, whole_lao, _ = hydrogen_lao()
whole_lao.Update()
whole = ao_of(whole_lao.GetOutput()).reshape(64, 64, 64)  # k, j, i
_, none_lao, _ = hydrogen_lao()
none_lao.SetRayVariationToNone()
none_lao.Update()
check(not np.array_equal(whole, ao_of(none_lao.GetOutput()).reshape(64, 64, 64)),
      "ROTATE changes the AO of hydrogen")
for ext in ((11, 40, 7, 50, 21, 52), (0, 63, 0, 63, 13, 30)):
    reader, piece_lao, _ = hydrogen_lao()
    piece_lao.UpdateExtent(ext)
    out = piece_lao.GetOutput()
    e = out.GetExtent()
    got = ao_of(out).reshape(e[5] - e[4] + 1, e[3] - e[2] + 1, e[1] - e[0] + 1)
    read = reader.GetOutput().GetExtent()
    check(any(read[2 * d] % 2 == 1 for d in range(3)),
          "the piece's input starts at an odd index on some axis (%s)" % (read,))
    check(e == ext and np.array_equal(got, whole[e[4]:e[5] + 1, e[2]:e[3] + 1, e[0]:e[1] + 1]),
          "ROTATE piece %s equals the whole volume's AO" % (ext,))

print("%d failure(s)" % len(failures))
sys.exit(1 if failures else 0)

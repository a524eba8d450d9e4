"""The ParaView plugin in pvpython or pvbatch, on a real volume
(Data/HeadMRVolume.mhd):

  TestPluginFilters.py load PLUGIN.so   -- LoadPlugin(path)
  TestPluginFilters.py env              -- found through PV_PLUGIN_PATH, no LoadPlugin

The three filter proxies exist, every property has documentation, the
enumerations and domains are the ones the XML promises (the reach bounded by
the data), and the proxies compute exactly what the VTK filters compute
(the same arrays, value for value) for LAO and for CAO at a clip pose."""
import os
import sys

from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403

mode = sys.argv[1]
data = os.environ["CAO_DATA_DIR"]
failures = []


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


if mode == "load":
    LoadPlugin(sys.argv[2], remote=False, ns=globals())
check("LocalAmbientOcclusion" in dir(sys.modules["paraview.simple"]) or
      "LocalAmbientOcclusion" in globals(), "the LocalAmbientOcclusion proxy is available (%s)" % mode)
import paraview.simple as pvs  # noqa: E402
LAO = getattr(pvs, "LocalAmbientOcclusion", None) or globals().get("LocalAmbientOcclusion")
MAPS = getattr(pvs, "ClipDepthMaps", None) or globals().get("ClipDepthMaps")
CAO = getattr(pvs, "ContextualAmbientOcclusion", None) or globals().get("ContextualAmbientOcclusion")
if not (LAO and MAPS and CAO):
    print("FAIL: the plugin's filters are missing")
    sys.exit(1)

reader = pvs.OpenDataFile(os.path.join(data, "HeadMRVolume.mhd"))
lao = LAO(Input=reader)
sphere = pvs.Sphere(Radius=40.0, ThetaResolution=32, PhiResolution=16)
maps = MAPS(Input=sphere)
cao = CAO(Input=lao, DepthMaps=maps)

# Documentation and domains.
for proxy in (lao, maps, cao):
    names = [n for n in proxy.ListProperties() if n not in ("Input", "DepthMaps")]
    undocumented = [n for n in names
                    if not proxy.GetProperty(n).SMProperty.GetDocumentation()]
    check(not undocumented, "%s: every property documented (missing: %s)"
          % (proxy.GetXMLName(), undocumented))
check(len(lao.GetProperty("RayPattern").Available) == 6 and
      lao.GetProperty("RayPattern").Available[2].startswith("26"), "ray patterns are an enumeration")
check(cao.GetProperty("Mode").Available == ["Subtraction", "Probing"], "the clip modes")

# The LAO quality settings: defaults and domains as the VTK filter's.
QUALITIES = ["Custom", "Low", "Medium", "High"]
VARIATIONS = ["None", "Rotate", "Jitter", "Rotate + Jitter"]


def range_domain(proxy, name):
    return proxy.GetProperty(name).SMProperty.FindDomain("vtkSMDoubleRangeDomain")


check(list(lao.GetProperty("Quality").Available) == QUALITIES and lao.Quality == "Low",
      "Quality: Custom, Low, Medium, High; default Low (%s)"
      % lao.Quality)
check(list(lao.GetProperty("RayVariation").Available) == VARIATIONS and lao.RayVariation == "None",
      "RayVariation: None, Rotate, Jitter, Rotate + Jitter; default None, Low "
      "quality's (%s)" % lao.RayVariation)
density, offset = range_domain(lao, "SampleDensity"), range_domain(lao, "StartOffset")
check(lao.SampleDensity == 1.0 and density is not None and density.GetMinimum(0) == 0.001,
      "SampleDensity: default 1 (Low quality's), at least 0.001 (%s)" % lao.SampleDensity)
check(lao.StartOffset == 0.5 and offset is not None and offset.GetMinimum(0) == 0.0 and
      offset.GetMaximum(0) == 0.999, "StartOffset: default 0.5, in [0, 0.999] (%s)" % lao.StartOffset)

# The representation's LAO settings: documented, with the same enumerations,
# and forwarded to the mapper.
rep = servermanager.ProxyManager().SMProxyManager.NewProxy(
    "representations", "ContextualAOVolumeRepresentation")
check(rep is not None, "the ContextualAOVolumeRepresentation proxy exists")
if rep is not None:
    def entries(name):
        d = rep.GetProperty(name).FindDomain("vtkSMEnumerationDomain")
        return [d.GetEntryText(i) for i in range(d.GetNumberOfEntries())] if d else None
    names = ("AOQuality", "AOSampleDensity", "AOStartOffset", "AORayVariation")
    check(all(rep.GetProperty(n) is not None and rep.GetProperty(n).GetDocumentation() for n in names),
          "the representation has documented %s" % (names,))
    check(entries("AOQuality") == QUALITIES and entries("AORayVariation") == VARIATIONS and
          rep.GetProperty("AOQuality").GetElement(0) == 1 and
          rep.GetProperty("AORayVariation").GetElement(0) == 0 and
          rep.GetProperty("AOSampleDensity").GetElement(0) == 1.0 and
          rep.GetProperty("AOStartOffset").GetElement(0) == 0.5,
          "the representation's quality enumerations and defaults")
    rep.GetProperty("AOQuality").SetElement(0, 2)
    rep.GetProperty("AORayVariation").SetElement(0, 3)
    rep.GetProperty("AOSampleDensity").SetElement(0, 1.5)
    rep.GetProperty("AOStartOffset").SetElement(0, 0.25)
    rep.UpdateVTKObjects()
    # (The plugin's representation class is not wrapped: reach the mapper,
    # which is, through its wrapped superclass's volume actor.)
    import contextualao  # noqa: E402,F401  (wraps vtkContextualAOVolumeMapper)
    mapper = rep.GetClientSideObject().GetActor().GetMapper()
    check((mapper.GetQuality(), mapper.GetRayVariation(), mapper.GetSampleDensity(),
           mapper.GetStartOffset()) == (2, 3, 1.5, 0.25),
          "the representation forwards the quality settings to the mapper")
    # Panel labels: ParaView splits an unlabelled "AOStrength" into
    # "A OStrength"; every AO property carries its own label.
    labels = {n: rep.GetProperty(n).GetXMLLabel() for n in
              ("AmbientOcclusion", "AOStrength", "AOCalibration", "AOQuality", "AORayPattern",
               "AONumberOfRays", "AOReach", "AONumberOfSamples", "AOSampleDensity",
               "AOStartOffset", "AORayVariation")}
    check(all(label and label.startswith(("AO ", "Ambient")) for label in labels.values()),
          "the representation's AO labels read 'AO ...': %s" % labels)
    # The AO calibration: half-space by default, forwarded, none available.
    check(entries("AOCalibration") == ["None (raw LAO)", "Half-space (open faces stay lit)"] and
          rep.GetProperty("AOCalibration").GetElement(0) == 1 and
          mapper.GetAOCalibration() == mapper.AO_CALIBRATION_HALF_SPACE,
          "the AO calibration defaults to half-space on the proxy and the mapper")
    rep.GetProperty("AOCalibration").SetElement(0, 0)
    rep.UpdateVTKObjects()
    check(mapper.GetAOCalibration() == mapper.AO_CALIBRATION_NONE,
          "the representation forwards AO Calibration = None to the mapper")

# The clip shape starts where it cuts what the view shows: at the centre of
# the data's +z face (ParaView's default camera looks down -z at it; at the
# data's centre it cut only the inside of a foggy volume), a quarter of its
# largest extent in size.
view = pvs.CreateView("RenderView")
display = pvs.Show(reader, view)
display.SetRepresentationType("Contextual AO Volume")
b = reader.GetDataInformation().GetBounds()
centre = [0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), b[5]]
quarter = 0.25 * max(b[1] - b[0], b[3] - b[2], b[5] - b[4])
check(list(display.ClipPosition) == centre and
      all(abs(s - quarter) < 1e-9 for s in display.ClipScale) and
      list(display.ClipReferenceBounds) == [-1, 1, -1, 1, -1, 1] and display.ClipUseReferenceBounds == 1,
      "the clip box defaults to the centre of the data's +z face %s, half-extents a quarter of its extent %g and "
      "the reference box [-1,1]^3 (%s, %s, %s, %s)"
      % (centre, quarter, list(display.ClipPosition), list(display.ClipScale),
         list(display.ClipReferenceBounds), display.ClipUseReferenceBounds))
# Choosing the representation colours by a point array when nothing is
# coloured, as choosing ParaView's Volume does (it stayed "Solid Color": an
# empty view), by the method and by the property alike.
check(display.ColorArrayName[0] == "POINTS" and display.ColorArrayName[1] != "",
      "SetRepresentationType('Contextual AO Volume') colours by a point array: %s"
      % list(display.ColorArrayName))
view2 = pvs.CreateView("RenderView")
display2 = pvs.Show(reader, view2)
pvs.ColorBy(display2, None)
display2.Representation = "Contextual AO Volume"
check(display2.ColorArrayName[1] != "", "Representation = 'Contextual AO Volume' colours by a point array: %s"
      % list(display2.ColorArrayName))
pvs.Delete(display)
pvs.Delete(view)

# A multi-component array: the panel offers it and Component picks one. The
# AO of component 1 of a 3-component (a, b, a) volume equals the AO of b.
import numpy  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy  # noqa: E402
from vtkmodules.vtkIOImage import vtkMetaImageReader as _HeadReader  # noqa: E402
_h = _HeadReader()
_h.SetFileName(os.path.join(data, "HeadMRVolume.mhd"))
_h.Update()
_a = vtk_to_numpy(_h.GetOutput().GetPointData().GetScalars())
_b = (_a // 2).astype(_a.dtype)


def _image(values, name):
    image = vtkImageData()
    image.CopyStructure(_h.GetOutput())
    array = numpy_to_vtk(numpy.ascontiguousarray(values), deep=1)
    array.SetName(name)
    image.GetPointData().SetScalars(array)
    return image


_abc = _image(numpy.stack([_a, _b, _a], axis=1), "abc")
_single = _image(_b, "b")
producer = pvs.TrivialProducer()
producer.GetClientSideObject().SetOutput(_abc)
producer.UpdatePipeline()
single = pvs.TrivialProducer()
single.GetClientSideObject().SetOutput(_single)
single.UpdatePipeline()

# Choosing Contextual AO Volume colours by the first one-component point
# array, not the first array: here a 3-component one comes first (it took
# that one, which the representation cannot draw, while it read the
# components of the outline the display showed before).
_two = _image(numpy.stack([_a, _b, _a], axis=1), "abc")
_b_array = numpy_to_vtk(numpy.ascontiguousarray(_b), deep=1)
_b_array.SetName("b")
_two.GetPointData().AddArray(_b_array)
two = pvs.TrivialProducer()
two.GetClientSideObject().SetOutput(_two)
two.UpdatePipeline()
view3 = pvs.CreateView("RenderView")
display3 = pvs.Show(two, view3)
pvs.ColorBy(display3, None)
display3.SetRepresentationType("Contextual AO Volume")
check(list(display3.ColorArrayName) == ["POINTS", "b"],
      "Contextual AO Volume on a 3-component and a 1-component array colours by the 1-component one: %s"
      % list(display3.ColorArrayName))
pvs.Delete(display3)
pvs.Delete(view3)


def _array_names(proxy):
    domain = proxy.GetProperty("SelectInputScalars").FindDomain("vtkSMArrayListDomain")
    return [domain.GetString(i) for i in range(domain.GetNumberOfStrings())]


pvs.SetActiveSource(producer)
multi = LAO(Input=producer)
check(list(multi.Scalars) == ["POINTS", "abc"] and "abc" in _array_names(multi)
      and multi.Component == -1 and "Component" in multi.ListProperties(),
      "the LAO proxy offers a 3-component array and a Component property (%s, %s)"
      % (list(multi.Scalars), multi.Component))
multi.Component = 1
multi.Backend = "CPU"
multi.UpdatePipeline()
pvs.SetActiveSource(single)
one = LAO(Input=single, Backend="CPU")
one.UpdatePipeline()
_m_ao = servermanager.Fetch(multi).GetPointData().GetArray("AmbientOcclusion")
_o_ao = servermanager.Fetch(one).GetPointData().GetArray("AmbientOcclusion")
check(_m_ao is not None and _o_ao is not None and _m_ao.GetNumberOfTuples() == _o_ao.GetNumberOfTuples()
      and all(_m_ao.GetValue(i) == _o_ao.GetValue(i) for i in range(_m_ao.GetNumberOfTuples())),
      "Component 1 of (a, b, a) gives the AO of b, value for value (%s vs %s)"
      % (_m_ao.GetRange() if _m_ao else None, _o_ao.GetRange() if _o_ao else None))
pvs.Delete(multi)
pvs.Delete(one)

# Volume formats VTK reads and ParaView 5.11 does not register: the plugin's
# reader proxies open them by extension.
import tempfile  # noqa: E402
from vtkmodules.vtkIOImage import vtkNIFTIImageWriter  # noqa: E402
slc = pvs.OpenDataFile(os.path.join(data, "neghip.slc"))
if slc:
    slc.UpdatePipeline()
check(slc is not None and slc.GetXMLName() == "CAOSLCReader" and
      tuple(slc.GetDataInformation().GetExtent()) == (0, 65, 0, 65, 0, 65),
      "OpenDataFile reads neghip.slc with the plugin's SLC reader (%s)"
      % (slc.GetXMLName() if slc else None))
from vtkmodules.vtkIOImage import vtkMetaImageReader as _MetaReader  # noqa: E402
_m = _MetaReader()
_m.SetFileName(os.path.join(data, "HeadMRVolume.mhd"))
_m.Update()
tmp = tempfile.mkdtemp()
for ext in ("nii", "nii.gz"):
    path = os.path.join(tmp, "head." + ext)
    w = vtkNIFTIImageWriter()
    w.SetInputData(_m.GetOutput())
    w.SetFileName(path)
    w.Write()
    nii = pvs.OpenDataFile(path)
    if nii:
        nii.UpdatePipeline()
    check(nii is not None and nii.GetXMLName() == "CAONIfTIReader" and
          tuple(nii.GetDataInformation().GetExtent()) == tuple(_m.GetOutput().GetExtent()),
          "OpenDataFile reads a .%s volume with the plugin's NIfTI reader" % ext)

# The same results as the VTK filters.
lao.Quality = "Custom"  # the settings below apply
lao.RayPattern = "14 rays (faces + corners)"
lao.Backend = "CPU"
maps.Reach = 32.0
maps.VoxelSpacing = [4.0, 4.0, 4.0]
cao.PoseTransform.Translate = [94.0, 122.0, 120.0]
cao.Backend = "CPU"
cao.UpdatePipeline()
pv_out = servermanager.Fetch(cao)
# The reach's range follows the data once its information is known.
reader.UpdatePipelineInformation()
lao.UpdatePipelineInformation()
reach = lao.GetProperty("Reach").SMProperty.FindDomain("vtkSMBoundsDomain")
check(reach is not None and abs(reach.GetMaximum(0) - 0.25 * 244.0) < 1e-6,
      "the reach is bounded by the data: up to a quarter of the largest extent (%s)"
      % (reach.GetMaximum(0) if reach else None))

import contextualao as vcao  # noqa: E402
from vtkmodules.vtkIOImage import vtkMetaImageReader  # noqa: E402
from vtkmodules.vtkFiltersSources import vtkSphereSource  # noqa: E402
from vtkmodules.vtkCommonTransforms import vtkTransform  # noqa: E402
r = vtkMetaImageReader()
r.SetFileName(os.path.join(data, "HeadMRVolume.mhd"))
v_lao = vcao.vtkLocalAmbientOcclusion()
v_lao.SetInputConnection(r.GetOutputPort())
v_lao.SetQualityToCustom()
v_lao.SetRayPattern(v_lao.RAYS_14)
v_lao.SetBackendToCPU()
s = vtkSphereSource()
s.SetRadius(40.0)
s.SetThetaResolution(32)
s.SetPhiResolution(16)
v_maps = vcao.vtkClipDepthMaps()
v_maps.SetInputConnection(s.GetOutputPort())
v_maps.SetReach(32.0)
v_maps.SetVoxelSpacing(4.0, 4.0, 4.0)
v_cao = vcao.vtkContextualAmbientOcclusion()
v_cao.SetInputConnection(v_lao.GetOutputPort())
v_cao.SetDepthMapsConnection(v_maps.GetOutputPort())
t = vtkTransform()
t.Translate(94.0, 122.0, 120.0)
v_cao.SetPoseTransform(t)
v_cao.SetBackendToCPU()
v_cao.Update()
v_out = v_cao.GetOutput()
for name in ("AmbientOcclusion", "ClipCategory", "ClippedOpacity"):
    a = pv_out.GetPointData().GetArray(name)
    b = v_out.GetPointData().GetArray(name)
    same = a is not None and b is not None and a.GetNumberOfTuples() == b.GetNumberOfTuples() and \
        all(a.GetValue(i) == b.GetValue(i) for i in range(a.GetNumberOfTuples()))
    check(same, "%s equals the VTK filters' value for value (%d voxels)"
          % (name, a.GetNumberOfTuples() if a else 0))
cats = pv_out.GetPointData().GetArray("ClipCategory").GetRange()
check(cats == (0.0, 2.0), "the pose clips some voxels, affects some, leaves some (%s)" % (cats,))

# AOFormat UNorm16 on the proxy: the AO as unsigned short, the VTK filter's
# float AO quantized (AO * 65535 + 0.5 in float, truncated).
check(cao.GetProperty("AOFormat").Available == ["Float", "UNorm16"] and cao.AOFormat == "Float",
      "the AO format is an enumeration, Float by default")
cao.AOFormat = "UNorm16"
cao.UpdatePipeline()
a16 = servermanager.Fetch(cao).GetPointData().GetArray("AmbientOcclusion")
bf = v_out.GetPointData().GetArray("AmbientOcclusion")
import numpy as _np  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy as _v2n  # noqa: E402
check(a16 is not None and a16.GetDataTypeAsString() == "unsigned short" and
      _np.array_equal(_v2n(a16), (_v2n(bf) * _np.float32(65535) + _np.float32(0.5)).astype(_np.uint16)),
      "AOFormat UNorm16: the AO is the float AO quantized, as unsigned short")
cao.AOFormat = "Float"


# A quality level on the LAO proxy: the same settings in effect
# (LAOSettings) and the same AO as the VTK filter with that level.
def lao_parameters(image):
    a = image.GetFieldData().GetArray("LAOSettings")
    return {a.GetComponentName(c): a.GetComponent(0, c) for c in range(a.GetNumberOfComponents())
            if a.GetComponentName(c) != "Milliseconds"} if a else {}


default_params = lao_parameters(servermanager.Fetch(lao))
check(len(default_params) == 11 and default_params["Quality"] == 0
      and default_params["Rays"] == 14,
      "the LAO proxy's LAOSettings: 12 components, Custom with the 14 rays set above (%s)"
      % default_params)
lao.Quality = "Medium"
lao.UpdatePipeline()
pv_level = servermanager.Fetch(lao)
v_lao.SetQualityToMedium()
v_lao.Update()
pv_params, v_params = lao_parameters(pv_level), lao_parameters(v_lao.GetOutput())
check(pv_params == v_params and pv_params["Quality"] == 2 and pv_params != default_params,
      "Quality Medium changes the proxy's LAOSettings as the VTK filter's: %s"
      % pv_params)
a = pv_level.GetPointData().GetArray("AmbientOcclusion")
b = v_lao.GetOutput().GetPointData().GetArray("AmbientOcclusion")
check(a is not None and a.GetNumberOfTuples() == b.GetNumberOfTuples() and
      all(a.GetValue(i) == b.GetValue(i) for i in range(a.GetNumberOfTuples())),
      "the Medium AO equals the VTK filter's value for value")

print("%d failure(s)" % len(failures))
sys.exit(1 if failures else 0)

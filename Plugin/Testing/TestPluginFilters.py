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
check(len(lao.GetProperty("RayPattern").Available) == 5 and
      lao.GetProperty("RayPattern").Available[2].startswith("26"), "ray patterns are an enumeration")
check(cao.GetProperty("Mode").Available == ["Subtraction", "Probing"], "the clip modes")

# The same results as the VTK filters.
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

print("%d failure(s)" % len(failures))
sys.exit(1 if failures else 0)

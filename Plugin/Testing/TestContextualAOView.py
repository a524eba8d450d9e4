"""The "Render View (Contextual AO)" view in pvpython: CreateView
("ContextualAORenderView") holds ParaView's representations and runs
vtkContextualAOPass between its camera pass and its default pass. A sphere
resting on a box (ParaView sources, drawn by composite mappers):
- the first frames voxelize, cast, trace and combine; against Surface AO
  Method None (the control) the picture only darkens, around the contact,
  not everywhere;
- a colour change runs only the combine; a camera turn casts and traces
  without a new grid; moving the sphere (its source) re-voxelizes;
- the view's properties reach the pass (Strength 0 leaves the picture);
- Surface AO Method Horizon Based and Volumetric: no grid, they darken
  around the contact only; Surface AO Indirect Light runs its step, and a
  colour change runs it and the combine alone;
- a volume in the same view ("Contextual AO Volume" of a block of image
  data beside the sphere) occludes the box under it, through its opacity;
  carving it all away with its Cube clip shape gives the box its own AO
  again, exactly; Volumes Occlude Surfaces off is the control; on the
  view's OpenGL the cones read it as on the CPU;
- selecting cells on the box with a rectangle (the hardware selector)
  works through the pass;
- with Surface AO Method None the view draws what ParaView's Render View
  draws, Hidden Line Removal on a wireframe sphere included (the renderer's
  own opaque path);
- with Tone Mapping on (an outer framebuffer pass) the AO still darkens the
  contact;
- ParaView's own Use Ambient Occlusion (vtkSSAOPass) applies only with
  Surface AO Method None (control: it darkens the picture there).
Writes OUT_DIR/view-off.png, view-on.png and view-volume.png.

  pvpython TestContextualAOView.py PLUGIN.so OUT_DIR   (under run-with-xvfb.sh)"""
import os
import sys

from paraview.simple import *  # noqa: F401,F403
from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.util.numpy_support import vtk_to_numpy

LoadPlugin(sys.argv[1], remote=False, ns=globals())
import contextualao  # noqa: E402,F401  (wraps vtkContextualAOPass)
out = sys.argv[2]
os.makedirs(out, exist_ok=True)
failures = []


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


def shot(name):
    path = os.path.join(out, name + ".png")
    SaveScreenshot(path, view, ImageResolution=[300, 240])
    r = vtkPNGReader()
    r.SetFileName(path)
    r.Update()
    return vtk_to_numpy(r.GetOutput().GetPointData().GetScalars()).astype(float)[:, :3].reshape(240, 300, 3)


view = CreateView("ContextualAORenderView")
view.OrientationAxesVisibility = 0
view.ViewSize = [300, 240]  # the screenshots' size: display coordinates are their pixels
check(view.GetClientSideObject().GetClassName() == "vtkPVRenderViewWithContextualAO",
      "the view is the plugin's (%s)" % view.GetClientSideObject().GetClassName())
box = Box(XLength=4.0, YLength=4.0, ZLength=0.4, Center=[0.0, 0.0, -0.2])
ball = Sphere(Center=[0.0, 0.0, 0.5], Radius=0.5, ThetaResolution=48, PhiResolution=24)
Show(box, view)
ballDisplay = Show(ball, view)
view.CameraPosition = [0.0, -6.0, 4.0]
view.CameraFocalPoint = [0.0, 0.0, 0.2]
view.CameraViewUp = [0.0, 0.0, 1.0]
view.SurfaceAORadius = 0.8
chain = view.GetRenderer().GetPass()
while chain is not None and chain.GetClassName() != "vtkContextualAOPass":
    chain = chain.GetDelegatePass() if hasattr(chain, "GetDelegatePass") else None
check(chain is not None, "the pass is in the view's render pass chain")
pas = chain
on = shot("view-on")
check(pas.GetVoxelizeCount() >= 1 and pas.GetTraceCount() >= 1 and "combine" in pas.GetLastFrameStages(),
      "the view voxelized, traced and combined: %s" % pas.GetLastFrameReport())
view.SurfaceAOMethod = "None"
off = shot("view-off")
check(pas.GetLastFrameStages() == "", "Surface AO Method None runs nothing")
# The AO only darkens, around the contact, and leaves most of the picture.
darker = (off - on).mean(axis=2)
changed = int((darker > 10).sum())
# FXAA (the Render View's default, now drawn by the pass too) re-blends the
# edge pixels next to darkened ones: up to 1 grey level brighter here, so 3
# is allowed; the AO itself never brightens.
check(darker.min() >= -3 and 300 < changed < 0.5 * darker.size,
      "AO only darkens (largest brightening %.1f), around the contact: %d of %d pixels darker by more "
      "than 10 grey levels" % (-darker.min(), changed, darker.size))
# ParaView's own screen-space AO (Use Ambient Occlusion) applies only while
# the method is None: with a method it would darken the surfaces twice.
# Set aside, it is said once (a trial saw it change nothing, silently);
# with Method None, where it applies, nothing is said (the control).
said = vtkStringOutputWindow()
previousWindow = vtkOutputWindow.GetInstance()
vtkOutputWindow.SetInstance(said)
view.UseAmbientOcclusion = 1
ssaoOff = shot("view-ssao-method-none")
saidWithNone = said.GetOutput()
view.SurfaceAOMethod = "Horizon Based"
ssaoOn = shot("view-ssao-hbao")
shot("view-ssao-hbao-again")  # (not Render(): paraview.simple's first Render resets the camera)
vtkOutputWindow.SetInstance(previousWindow)
note = "Use Ambient Occlusion (ParaView's screen-space AO) is not applied"
check(note not in saidWithNone and said.GetOutput().count(note) == 1,
      "ParaView's own AO set aside is said once over two frames, and not while it applies: %r"
      % said.GetOutput()[-400:])
view.UseAmbientOcclusion = 0
hbao = shot("view-hbao")
check(abs(ssaoOff - off).max() > 30 and abs(ssaoOn - hbao).max() == 0,
      "Use Ambient Occlusion darkens the picture with Method None (by up to %.0f levels: the control) "
      "and changes nothing with Horizon Based (%.0f)" % (abs(ssaoOff - off).max(), abs(ssaoOn - hbao).max()))
view.SurfaceAOMethod = "Voxel Cones"
Render(view)
grids, traces = pas.GetVoxelizeCount(), pas.GetTraceCount()
ballDisplay.AmbientColor = ballDisplay.DiffuseColor = [0.9, 0.3, 0.2]
Render(view)
check(pas.GetLastFrameStages() == "combine" and pas.GetVoxelizeCount() == grids and pas.GetTraceCount() == traces,
      "a colour change runs only the combine (%s)" % pas.GetLastFrameStages())
view.GetActiveCamera().Azimuth(15)
Render(view)
check(pas.GetLastFrameStages() == "primary,trace,combine" and pas.GetVoxelizeCount() == grids,
      "a camera turn casts and traces without a new grid (%s)" % pas.GetLastFrameStages())
ball.Center = [0.3, 0.0, 0.5]
Render(view)
check(pas.GetVoxelizeCount() == grids + 1 and pas.GetLastFrameStages().startswith("voxelize"),
      "moving the sphere's source re-voxelizes (%s)" % pas.GetLastFrameStages())
# Surface AO Backend OpenGL: the grid and the cones on the view's own
# OpenGL (llvmpipe under Xvfb here): the same picture as the CPU's to a
# grey level, and the report says where it ran.
view.SurfaceAOGBuffer = "Ray Cast"
view.SurfaceAOBackend = "CPU"
cpu = shot("view-cpu")
view.SurfaceAOBackend = "OpenGL"
gpu = shot("view-opengl")
report = pas.GetLastFrameReport()
check('"backend": "OpenGL' in report and pas.GetLastFrameStages().startswith("voxelize") and
      abs(gpu - cpu).max() <= 2,
      "Surface AO Backend OpenGL: voxelized and traced on the view's OpenGL (%s), the picture within %.0f grey "
      "levels of the CPU's" % (pas.GetLastFrameStages(), abs(gpu - cpu).max()))
# G Buffer Auto (the default) with OpenGL: the drawn depth, and the whole
# frame on the view's OpenGL (ParaView's own framebuffer): the picture as
# the CPU's from the same depth G-buffer, to a grey level or two; Auto with
# the CPU backend is the ray cast.
view.SurfaceAOGBuffer = "Depth Buffer"
view.SurfaceAOBackend = "CPU"
cpuDepth = shot("view-cpu-depth")
view.SurfaceAOGBuffer = "Auto"
view.SurfaceAOBackend = "OpenGL"
gpuFrame = shot("view-opengl-frame")
report = pas.GetLastFrameReport()
apart = int((abs(gpuFrame - cpu).max(axis=2) > 2).sum())
check('"frame_on_gpu": true' in report and '"gbuffer": "depth buffer (auto)"' in report and
      abs(gpuFrame - cpuDepth).max() <= 2 and apart >= 20,
      "G Buffer Auto with OpenGL: the frame stays on the view's OpenGL (%s), the picture within %.0f grey levels "
      "of the CPU's depth G-buffer (and not the ray cast's: %d pixels more than 2 levels apart)"
      % (pas.GetLastFrameStages(), abs(gpuFrame - cpuDepth).max(), apart))
view.SurfaceAOBackend = "CPU"
Render(view)
check('"gbuffer": "ray cast (auto)"' in pas.GetLastFrameReport(), "G Buffer Auto on the CPU: the ray cast")
view.SurfaceAOBackend = "Auto"
Render(view)
view.SurfaceAOStrength = 0.0
a = shot("view-strength0")
view.SurfaceAOMethod = "None"
b = shot("view-none")
check(abs(a - b).max() <= 1, "Strength 0 leaves the picture as Method None (max diff %.0f)" % abs(a - b).max())
view.SurfaceAOStrength = 1.0
# The screen-space methods: no grid; they darken around the contact only;
# Volumetric's indirect light runs its own step (and only it and the
# combine on a colour change).
for method in ("Horizon Based", "Volumetric"):
    grids = pas.GetVoxelizeCount()
    view.SurfaceAOMethod = method
    img = shot("view-" + method.split()[0].lower())
    stages = pas.GetLastFrameStages()
    d = (b - img).mean(axis=2)
    check(pas.GetVoxelizeCount() == grids and "trace" in stages and "voxelize" not in stages and
          d.min() >= -3 and 200 < int((d > 10).sum()) < 0.5 * d.size,
          "%s: no grid (%s); darkens %d pixels by more than 10 grey levels, brightens none by more than 3"
          % (method, stages, int((d > 10).sum())))
view.SurfaceAOIndirectLight = 1
Render(view)
first = pas.GetLastFrameStages()
ballDisplay.AmbientColor = ballDisplay.DiffuseColor = [0.2, 0.9, 0.3]
Render(view)
check("indirect" in first and pas.GetLastFrameStages() == "indirect,combine" and '"indirect_light": true' in
      pas.GetLastFrameReport(), "Surface AO Indirect Light: its step runs (%s), a colour change runs it and the "
      "combine only (%s)" % (first, pas.GetLastFrameStages()))
view.SurfaceAOIndirectLight = 0
ballDisplay.AmbientColor = ballDisplay.DiffuseColor = [0.9, 0.3, 0.2]
view.SurfaceAOMethod = "Voxel Cones"

# A volume in the same view: a block of image data on the box, beside the
# sphere, drawn by the contextual AO volume representation.
block = ProgrammableSource(OutputDataSetType="vtkImageData")
block.ScriptRequestInformation = """
from paraview import util
util.SetOutputWholeExtent(self, [0, 10, 0, 20, 0, 8])
"""
block.Script = """
import numpy
out = self.GetOutput()
out.SetExtent(0, 10, 0, 20, 0, 8)
out.SetOrigin(0.9, -1.0, 0.05)
out.SetSpacing(0.1, 0.1, 0.1)
values = numpy.ones(11 * 21 * 9)
from vtkmodules.util.numpy_support import numpy_to_vtk
a = numpy_to_vtk(values, deep=1)
a.SetName("density")
out.GetPointData().SetScalars(a)
"""
blockDisplay = Show(block, view)
ColorBy(blockDisplay, ("POINTS", "density"))
blockDisplay.SetRepresentationType("Contextual AO Volume")
blockOpacity = GetOpacityTransferFunction("density")
blockOpacity.Points = [0.0, 0.0, 0.5, 0.0, 1.0, 0.3, 0.5, 0.0]
blockDisplay.ScalarOpacityUnitDistance = 0.2
blockDisplay.ClipShape = "None"
Render(view)
# Where the box's top under the block projects (display coordinates).
ren = view.GetRenderer()
ren.SetWorldPoint(1.4, -0.5, 0.0, 1.0)
ren.WorldToDisplay()
px, py = [int(v) for v in ren.GetDisplayPoint()[:2]]
under = pas.GetPixelAO(px, py)
report = pas.GetLastFrameReport()
view.VolumesOccludeSurfaces = 0
Render(view)
alone = pas.GetPixelAO(px, py)
check('"occluding_volumes": 1' in report and under < alone - 0.1,
      "the volume occludes the box under it: AO %.3f against %.3f without (%s)" % (under, alone, report))
view.VolumesOccludeSurfaces = 1
shot("view-volume")
blockDisplay.ClipShape = "Cube"
blockDisplay.ClipPosition = [1.4, 0.0, 0.45]
blockDisplay.ClipScale = [0.7, 1.2, 0.6]
Render(view)
carved = pas.GetPixelAO(px, py)
check("volumes" in pas.GetLastFrameStages() and carved == alone,
      "carving the block away with its Cube gives the box its own AO: %.3f (%s)"
      % (carved, pas.GetLastFrameStages()))
# On the view's own OpenGL (Surface AO Backend OpenGL; G Buffer Auto: the
# frame on the GPU) the cones read the block as the CPU's do: the box's AO
# under it as above (the drawn depth's positions against the ray cast's:
# within 0.01; the block's darkening is over 0.1).
blockDisplay.ClipShape = "None"
view.SurfaceAOBackend = "OpenGL"
Render(view)
underGL = pas.GetPixelAO(px, py)
reportGL = pas.GetLastFrameReport()
check('"backend": "OpenGL' in reportGL and '"occluding_volumes": 1' in reportGL and
      '"frame_on_gpu": true' in reportGL and abs(underGL - under) < 0.01,
      "Surface AO Backend OpenGL: the cones read the block, AO %.4f against the CPU's %.4f (%s)"
      % (underGL, under, reportGL))
view.SurfaceAOBackend = "Auto"

# Selection through the pass (the renderer's own path draws the ids).
blockDisplay.Visibility = 0
SetActiveSource(box)
SelectSurfaceCells(Rectangle=[20, 20, 280, 100], View=view)
picked = ExtractSelection(Input=box)
picked.UpdatePipeline()
cells = picked.GetDataInformation().GetNumberOfCells()
check(cells > 0, "a rectangle selection on the box through the pass selects %d cell(s)" % cells)

# Method None draws as the Render View, hidden-line removal included.
ballDisplay.SetRepresentationType("Wireframe")
view.HiddenLineRemoval = 1
view.SurfaceAOMethod = "None"
plain = CreateView("RenderView")
plain.OrientationAxesVisibility = 0
plain.ViewSize = [300, 240]
plain.HiddenLineRemoval = 1
Show(box, plain)
plainBall = Show(ball, plain)
plainBall.SetRepresentationType("Wireframe")
plainBall.AmbientColor = plainBall.DiffuseColor = [0.9, 0.3, 0.2]
for prop in ("CameraPosition", "CameraFocalPoint", "CameraViewUp", "CameraViewAngle"):
    setattr(plain, prop, getattr(view, prop))
mine = shot("view-none-hlr")
path = os.path.join(out, "render-view-hlr.png")
SaveScreenshot(path, plain, ImageResolution=[300, 240])
r = vtkPNGReader()
r.SetFileName(path)
r.Update()
theirs = vtk_to_numpy(r.GetOutput().GetPointData().GetScalars()).astype(float)[:, :3].reshape(240, 300, 3)
differ = int((abs(mine - theirs).max(axis=2) > 1).sum())
check(differ == 0, "Method None with Hidden Line Removal draws as the Render View (%d pixels differ)" % differ)
Delete(plain)
ballDisplay.SetRepresentationType("Surface")
view.HiddenLineRemoval = 0
# Tone mapping: an outer framebuffer pass around the AO.
view.UseToneMapping = 1
view.SurfaceAOMethod = "None"
toneOff = shot("view-tone-off")
view.SurfaceAOMethod = "Voxel Cones"
toneOn = shot("view-tone-on")
darker = int(((toneOff - toneOn).mean(axis=2) > 10).sum())
check(darker > 300, "with Tone Mapping the AO darkens %d pixels by more than 10 grey levels" % darker)
view.UseToneMapping = 0
print("%d failure(s)" % len(failures))
sys.stdout.flush()
os._exit(1 if failures else 0)

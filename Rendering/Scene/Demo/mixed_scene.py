"""The mixed scene: every kind of geometry with its AO in one frame.

carotid.vtk drawn three ways at once, in the project's EGL window (no X):
  - the volume (its scalars, the vessels) by vtkContextualAOVolumeMapper,
    carved by a clip sphere that moves along a path through the
    bifurcation: the volume's AO is updated contextually at every pose;
  - an isosurface of the same scalars inside the vessels (value 350, the
    brightest flow), revealed where the clip carves the volume;
  - streamline tubes of its velocity, traced from seeds in the bifurcation;
and vtkContextualAOPass (voxel cone tracing by default) gives the
isosurface and the tubes their AO, with the volume occluding them (the
volume's clipped opacity: carving it lightens the surfaces near the cut).

Each pose is drawn with AO (volume AO on, the pass on) and without (volume
AO off, pass method NONE), and the two are put side by side (AO off | AO
on). Writes, in OUT_DIR:
  mixed_%03d.png (AO on), mixed_noao_%03d.png (AO off),
  mixed_side_%03d.png (AO off | AO on),
  mixed_report.json (per AO-on frame: the pass's and the mapper's reports),
and with --masks, mixed_mask_{volume,isosurface,tubes}_%03d.png: each kind
drawn alone (white where it covers a pixel), for tests that measure each
kind's AO in the picture.

  PYTHONPATH=build/python /usr/bin/python3 Rendering/Scene/Demo/mixed_scene.py \\
      Data/carotid.vtk OUT_DIR [--frames 12] [--image 640x480] [--method vct]
      [--occluding-volumes on|off] [--masks]
"""
import argparse
import json
import os
import sys

from contextualao import (vtkContextualAOEGLWindow, vtkContextualAOPass,
                          vtkContextualAOVolumeMapper)
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkFiltersCore import vtkContourFilter, vtkPolyDataNormals, vtkTubeFilter
from vtkmodules.vtkFiltersFlowPaths import vtkStreamTracer
from vtkmodules.vtkFiltersSources import vtkPointSource, vtkSphereSource
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkIOLegacy import vtkDataSetReader
from vtkmodules.vtkRenderingCore import (vtkActor, vtkColorTransferFunction, vtkPolyDataMapper,
                                         vtkRenderer, vtkVolume, vtkVolumeProperty,
                                         vtkWindowToImageFilter)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (the OpenGL factories)
import vtkmodules.vtkRenderingVolumeOpenGL2  # noqa: F401

METHODS = {"none": vtkContextualAOPass.NONE, "vct": vtkContextualAOPass.VCT,
           "hbao": vtkContextualAOPass.HBAO, "volumetric": vtkContextualAOPass.VOLUMETRIC}

parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
parser.add_argument("volume", help="carotid.vtk (scalars and velocity vectors)")
parser.add_argument("out", help="output folder")
parser.add_argument("--frames", type=int, default=12, help="poses of the clip path (default 12)")
parser.add_argument("--image", default="640x480", help="frame size WxH (default 640x480)")
parser.add_argument("--method", choices=sorted(METHODS), default="vct",
                    help="the surfaces' AO method in the AO-on frames (default vct)")
parser.add_argument("--occluding-volumes", choices=("on", "off"), default="on",
                    help="whether the volume occludes the surfaces (default on)")
parser.add_argument("--surfaces-occlude-volume", choices=("on", "off"), default="on",
                    help="whether the isosurface occludes the volume's AO (default on)")
parser.add_argument("--masks", action="store_true", help="also write each kind drawn alone")
args = parser.parse_args()
if args.frames < 1 or args.frames > 1000:
    sys.exit("mixed_scene.py: --frames must be 1 to 1000, not %d" % args.frames)
try:
    width, height = (int(v) for v in args.image.lower().split("x"))
    if not (16 <= width <= 8192 and 16 <= height <= 8192):
        raise ValueError
except ValueError:
    sys.exit("mixed_scene.py: --image must be WxH, each 16 to 8192, not %r" % args.image)
os.makedirs(args.out, exist_ok=True)

reader = vtkDataSetReader()
reader.SetFileName(args.volume)
reader.Update()
data = reader.GetOutput()
if (data is None or not data.IsA("vtkImageData") or data.GetPointData().GetScalars() is None
        or data.GetPointData().GetVectors() is None):
    sys.exit("mixed_scene.py: %s must be image data with point scalars and vectors "
             "(carotid.vtk)" % args.volume)

window = vtkContextualAOEGLWindow()
window.SetSize(width, height)
if not window.IsUsable():
    sys.exit("mixed_scene.py: no EGL OpenGL 4.3 context for the window: %s" % window.GetContextError())
renderer = vtkRenderer()
renderer.SetBackground(1, 1, 1)
window.AddRenderer(renderer)

# The volume: the vessels (scalars above 150), carved by the clip sphere.
color = vtkColorTransferFunction()
color.AddRGBPoint(0, 0.2, 0.3, 0.6)
color.AddRGBPoint(150, 0.9, 0.8, 0.7)
color.AddRGBPoint(580, 1.0, 0.9, 0.8)
opacity = vtkPiecewiseFunction()
opacity.AddPoint(0, 0.0)
opacity.AddPoint(150, 0.0)
opacity.AddPoint(260, 0.9)
opacity.AddPoint(580, 0.95)
volumeProperty = vtkVolumeProperty()
volumeProperty.SetColor(color)
volumeProperty.SetScalarOpacity(opacity)
volumeProperty.ShadeOn()
volumeProperty.SetAmbient(0.6)  # the AO scales the ambient term (as cao render lights it)
volumeProperty.SetDiffuse(0.5)
volumeProperty.SetInterpolationTypeToLinear()
volumeMapper = vtkContextualAOVolumeMapper()
volumeMapper.SetInputConnection(reader.GetOutputPort())
volume = vtkVolume()
volume.SetMapper(volumeMapper)
volume.SetProperty(volumeProperty)
renderer.AddVolume(volume)
sphere = vtkSphereSource()
sphere.SetRadius(12)
sphere.SetThetaResolution(48)
sphere.SetPhiResolution(24)
sphereMapper = vtkPolyDataMapper()
sphereMapper.SetInputConnection(sphere.GetOutputPort())
clip = vtkActor()  # the clip shape's pose and mesh; not drawn
clip.SetMapper(sphereMapper)
volumeMapper.SetClipShape(clip)

# The isosurface and the streamline tubes.
contour = vtkContourFilter()
contour.SetInputConnection(reader.GetOutputPort())
contour.SetValue(0, 350)
normals = vtkPolyDataNormals()
normals.SetInputConnection(contour.GetOutputPort())
seeds = vtkPointSource()
seeds.SetNumberOfPoints(60)
seeds.SetCenter(137, 104, 23)
seeds.SetRadius(8)
lines = vtkStreamTracer()
lines.SetInputConnection(reader.GetOutputPort())
lines.SetSourceConnection(seeds.GetOutputPort())
lines.SetIntegratorTypeToRungeKutta4()
lines.SetMaximumPropagation(300)
lines.SetIntegrationDirectionToBoth()
tubes = vtkTubeFilter()
tubes.SetInputConnection(lines.GetOutputPort())
tubes.SetRadius(0.3)
tubes.SetNumberOfSides(8)
surfaces = {}
for name, source, rgb in (("isosurface", normals, (0.85, 0.35, 0.3)),
                          ("tubes", tubes, (0.3, 0.6, 0.9))):
    mapper = vtkPolyDataMapper()
    mapper.SetInputConnection(source.GetOutputPort())
    mapper.ScalarVisibilityOff()
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetColor(*rgb)
    actor.GetProperty().SetAmbient(0.4)
    actor.GetProperty().SetDiffuse(0.6)
    renderer.AddActor(actor)
    surfaces[name] = actor
if args.surfaces_occlude_volume == "on":
    # The isosurface (closed) is opaque for the volume's LAO: the vessel
    # around it darkens. (The tubes are open meshes: they do not.)
    volumeMapper.AddOccluder(surfaces["isosurface"])

aoPass = vtkContextualAOPass()
aoPass.SetOccludingVolumes(args.occluding_volumes == "on")
renderer.SetPass(aoPass)
renderer.ResetCamera()
camera = renderer.GetActiveCamera()
camera.Elevation(20)
camera.Azimuth(30)
camera.Zoom(1.5)
renderer.ResetCameraClippingRange()


def pose(k):
    """The clip sphere's centre at pose k: along the bifurcation and back up."""
    t = k / max(args.frames - 1, 1)
    return (123.0 + 30.0 * t, 100.0 + 8.0 * t, 23.0 - 4.0 * t)


def write(path):
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.ReadFrontBufferOff()
    grab.ShouldRerenderOff()  # the frame just drawn, not a second render
    grab.Update()
    png = vtkPNGWriter()
    png.SetFileName(os.path.join(args.out, path))
    png.SetInputConnection(grab.GetOutputPort())
    png.Write()
    return grab.GetOutput()


def draw(ao, pattern):
    """Every pose of the path, in order, with the AO on or off."""
    volumeMapper.SetAmbientOcclusion(ao)
    aoPass.SetMethod(METHODS[args.method] if ao else vtkContextualAOPass.NONE)
    aoPass.SetLineMethod(vtkContextualAOPass.LINE_PRISMS if ao else vtkContextualAOPass.LINE_NONE)
    reports = []
    for k in range(args.frames):
        clip.SetPosition(*pose(k))
        window.Render()
        write(pattern % k)
        reports.append({"pose": k, "centre": pose(k),
                        "pass": json.loads(aoPass.GetLastFrameReport()),
                        "volume": json.loads(volumeMapper.GetLastFrameReport())})
    return reports


report = draw(True, "mixed_%03d.png")
draw(False, "mixed_noao_%03d.png")
with open(os.path.join(args.out, "mixed_report.json"), "w") as f:
    json.dump(report, f, indent=1)

# AO off | AO on.
from vtkmodules.vtkFiltersCore import vtkImageAppend  # noqa: E402
from vtkmodules.vtkImagingCore import vtkImageExtractComponents  # noqa: E402
from vtkmodules.vtkIOImage import vtkPNGReader  # noqa: E402
for k in range(args.frames):
    row = vtkImageAppend()
    for name in ("mixed_noao_%03d.png", "mixed_%03d.png"):
        png = vtkPNGReader()
        png.SetFileName(os.path.join(args.out, name % k))
        rgb = vtkImageExtractComponents()
        rgb.SetInputConnection(png.GetOutputPort())
        rgb.SetComponents(0, 1, 2)
        row.AddInputConnection(rgb.GetOutputPort())
    png = vtkPNGWriter()
    png.SetFileName(os.path.join(args.out, "mixed_side_%03d.png" % k))
    png.SetInputConnection(row.GetOutputPort())
    png.Write()

if args.masks:
    # Each kind alone, AO off, in white on black: where it covers a pixel.
    aoPass.SetMethod(vtkContextualAOPass.NONE)
    aoPass.SetLineMethod(vtkContextualAOPass.LINE_NONE)
    volumeMapper.SetAmbientOcclusion(False)
    renderer.SetBackground(0, 0, 0)
    kinds = {"volume": volume, "isosurface": surfaces["isosurface"], "tubes": surfaces["tubes"]}
    for name, prop in kinds.items():
        for other in kinds.values():
            other.SetVisibility(other is prop)
        for k in range(args.frames):
            clip.SetPosition(*pose(k))
            window.Render()
            write("mixed_mask_%s_%03d.png" % (name, k))
    for prop in kinds.values():
        prop.SetVisibility(True)

print("wrote %s/mixed_000.png .. mixed_%03d.png (AO on), mixed_noao_*.png (AO off), "
      "mixed_side_*.png (AO off | AO on) and mixed_report.json" % (args.out, args.frames - 1))

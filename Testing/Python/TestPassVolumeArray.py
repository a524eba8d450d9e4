"""A volume occludes the surfaces through the array its mapper draws, not
the input's active scalars (vtkContextualAOPass, voxel cones).

ParaView's "Color by" selects a point array on the volume's mapper (scalar
mode "use point field data" and an array name) and leaves the input's
active scalars alone: a new-user trial coloured a resampled volume by
Temp, whose active scalars were another array or none, and the volume
drew but did not darken the floor under it ("the volume's input is not
image data with point scalars").

Checked in the project's EGL window: an image of 32^3 with two point
arrays, "Zero" (all 0, the active scalars) and "Block" (an opaque block in
its middle), drawn by vtkContextualAOVolumeMapper coloured by "Block",
over a slab:
- the pass counts one occluding volume, and the slab right under the
  block is darker than with the volume hidden (the AO at the pixel under
  its centre: below 0.9 of the hidden case's);
- coloured by "Zero" (transparent everywhere) it darkens nothing there
  (the negative control: the same pixel within 0.01 of the hidden case's).
"""
import json
import sys

from contextualao import vtkContextualAOPass, vtkContextualAOVolumeMapper
from vtkmodules.vtkCommonCore import vtkFloatArray
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPiecewiseFunction
from vtkmodules.vtkFiltersSources import vtkCubeSource
from vtkmodules.vtkRenderingCore import (vtkActor, vtkColorTransferFunction, vtkPolyDataMapper, vtkVolume,
                                         vtkVolumeProperty)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401

from neghip_scene import window_and_renderer  # (this folder)

failures = []


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


window, renderer = window_and_renderer(240)

n = 32
image = vtkImageData()
image.SetDimensions(n, n, n)
image.SetOrigin(-16, -16, 1)  # its lowest slice 1 above the slab's top
zero, block = vtkFloatArray(), vtkFloatArray()
zero.SetName("Zero")
block.SetName("Block")
for k in range(n):
    for j in range(n):
        for i in range(n):
            zero.InsertNextValue(0.0)
            block.InsertNextValue(255.0 if 8 <= i < 24 and 8 <= j < 24 and k < 12 else 0.0)
image.GetPointData().AddArray(block)
image.GetPointData().SetScalars(zero)  # the active scalars: another array

opacity = vtkPiecewiseFunction()
opacity.AddPoint(0, 0.0)
opacity.AddPoint(255, 1.0)
color = vtkColorTransferFunction()
color.AddRGBPoint(0, 0.8, 0.8, 0.8)
color.AddRGBPoint(255, 0.8, 0.8, 0.8)
prop = vtkVolumeProperty()
prop.SetScalarOpacity(opacity)
prop.SetColor(color)
mapper = vtkContextualAOVolumeMapper()
mapper.SetInputData(image)
mapper.SetScalarModeToUsePointFieldData()
mapper.SelectScalarArray("Block")
volume = vtkVolume()
volume.SetMapper(mapper)
volume.SetProperty(prop)
renderer.AddVolume(volume)

slab = vtkCubeSource()
slab.SetBounds(-40, 40, -40, 40, -1, 0)
slab_mapper = vtkPolyDataMapper()
slab_mapper.SetInputConnection(slab.GetOutputPort())
floor = vtkActor()
floor.SetMapper(slab_mapper)
floor.GetProperty().SetAmbient(0.4)
floor.GetProperty().SetDiffuse(0.6)
renderer.AddActor(floor)

# From above and in front: the floor just before the block's front face
# (y = -8), which the block occludes, is in sight.
renderer.ResetCamera()
camera = renderer.GetActiveCamera()
camera.SetFocalPoint(0, 0, 0)
camera.SetPosition(0, -60, 90)
camera.SetViewUp(0, 0, 1)
renderer.ResetCameraClippingRange()

ao = vtkContextualAOPass()
renderer.SetPass(ao)


def floor_ao():
    """The AO of the floor pixels just beside the block's front edge."""
    window.Render()
    report = json.loads(ao.GetLastFrameReport())
    values = []
    w, h = window.GetSize()
    # Project world points on the floor 1.5 in front of the block's front edge.
    for x in (-4.0, 0.0, 4.0):
        renderer.SetWorldPoint(x, -9.5, 0.0, 1.0)
        renderer.WorldToDisplay()
        px, py, _ = renderer.GetDisplayPoint()
        v = ao.GetPixelAO(int(px), int(py))
        if v >= 0:
            values.append(v)
    return report, (sum(values) / len(values) if values else -1.0)


volume.VisibilityOff()
_, hidden = floor_ao()
volume.VisibilityOn()
report, shown = floor_ao()
print("floor beside the block: AO %.3f with the volume coloured by Block, %.3f with it hidden; "
      "occluding volumes %s" % (shown, hidden, report.get("occluding_volumes")))
check(report.get("occluding_volumes") == 1, "the volume coloured by a non-active array occludes: %s"
      % report.get("occluding_volumes"))
check(hidden > 0 and 0 <= shown < 0.9 * hidden,
      "the block (the drawn array) darkens the floor beside it: %.3f against %.3f" % (shown, hidden))
mapper.SelectScalarArray("Zero")
_, transparent = floor_ao()
print("coloured by Zero: %.3f" % transparent)
check(abs(transparent - hidden) <= 0.01,
      "the negative control: coloured by the all-zero array it darkens nothing (%.3f against %.3f)"
      % (transparent, hidden))

if failures:
    print("FAILED: %d check(s)" % len(failures))
    sys.exit(1)
print("all checks passed")

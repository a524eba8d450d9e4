"""The scene's surfaces and lines occlude the volume's AO through
vtkContextualAOPass (GeometryOccludesVolumeAO), judged in the picture:
neghip.slc drawn by vtkContextualAOVolumeMapper with a bundle of
streamline-like lines and a ball inside it, in the project's EGL window.

- Off (the default): the volume's frame is a mapper's without occluders,
  pixel for pixel (the pass adds nothing).
- On: the pass makes the visible opaque actors the mapper's occluders (the
  mapper's report counts the voxels made opaque by 2 occluders), and the frame
  equals, pixel for pixel, that of the same scene whose mapper was given
  the two actors by hand (AddOccluder): the pass adds no effect of its own.
  The lines and the ball darken the volume (against the frame with the
  property off: the differing pixels are darker on average).
- Moving the lines is an opacity edit (fewer voxels recomputed than the
  volume has); a camera turn and a colour change of the lines recompute
  nothing (the mapper's report: no reason, no voxel recomputed).
- Hiding the lines removes them from the occluders; turning the property
  off empties the list the pass set.
- A mapper given its own occluder by the application keeps it (the pass
  leaves its list alone); an emptied list is filled again; a volume taken
  out of the renderer keeps none of the pass's occluders.
"""
import json
import os
import sys

import numpy as np
from contextualao import vtkContextualAOPass
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkIOImage import vtkSLCReader
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper

from neghip_scene import add_volume, frame, oblique_camera, window_and_renderer  # (this folder)

data = os.environ.get("CAO_DATA_DIR", "Data")
failures = []


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what, flush=True)
    if not ok:
        failures.append(what)


reader = vtkSLCReader()
reader.SetFileName(os.path.join(data, "neghip.slc"))
reader.Update()
voxels = reader.GetOutput().GetNumberOfPoints()

# A bundle of 9 lines along x through the matter, and a ball.
points, cells = vtkPoints(), vtkCellArray()
for dy in (-2, 0, 2):
    for dz in (-2, 0, 2):
        cells.InsertNextCell(16)
        for x in range(10, 56, 3):
            cells.InsertCellPoint(points.InsertNextPoint(x, 30 + dy, 30 + dz))
bundle = vtkPolyData()
bundle.SetPoints(points)
bundle.SetLines(cells)
ball = vtkSphereSource()
ball.SetCenter(44, 40, 38)
ball.SetRadius(5)
ball.SetThetaResolution(24)
ball.SetPhiResolution(16)
ball.Update()


class Scene:
    def __init__(self, wired=False, by_hand=False):
        self.window, self.renderer = window_and_renderer()
        self.mapper = add_volume(self.renderer, reader)
        self.actors = []
        for source in (bundle, ball.GetOutput()):
            m = vtkPolyDataMapper()
            m.SetInputData(source)
            actor = vtkActor()
            actor.SetMapper(m)
            actor.GetProperty().SetColor(0.3, 0.5, 0.9)
            actor.GetProperty().SetLineWidth(2)
            self.renderer.AddActor(actor)
            self.actors.append(actor)
            if by_hand:
                self.mapper.AddOccluder(actor)
        self.aoPass = vtkContextualAOPass()
        # (the surfaces' and lines' AO is not what is judged here)
        self.aoPass.SetMethod(vtkContextualAOPass.NONE)
        self.aoPass.SetLineMethod(vtkContextualAOPass.LINE_NONE)
        self.aoPass.SetGeometryOccludesVolumeAO(wired)
        self.renderer.SetPass(self.aoPass)
        oblique_camera(self.renderer)

    def frame(self):
        return frame(self.window)

    def report(self):
        return json.loads(self.mapper.GetLastFrameReport())


plain = Scene()
plainFrame = plain.frame()
check(plain.mapper.GetNumberOfOccluders() == 0, "off (the default): the pass adds no occluder")

scene = Scene(wired=True)
wiredFrame = scene.frame()
report = scene.report()
check(scene.mapper.GetNumberOfOccluders() == 2 and
      any("made opaque by 2 occluder(s)" in r for r in report["reasons"]),
      "on: the lines and the ball are the mapper's occluders (%s)" % report["reasons"])
hand = Scene(by_hand=True)
handFrame = hand.frame()
check(np.array_equal(wiredFrame, handFrame),
      "on: the frame equals that of the mapper given the two actors by hand (largest difference %d)"
      % np.abs(wiredFrame - handFrame).max())
lum = lambda a: a @ np.array([0.2126, 0.7152, 0.0722])
differ = np.abs(lum(wiredFrame) - lum(plainFrame)) > 2
darker = float(np.mean(lum(plainFrame)[differ] - lum(wiredFrame)[differ])) if differ.any() else 0.0
check(differ.sum() > 100 and darker > 2,
      "the lines and the ball darken the volume (%d pixels differ, %.1f levels darker on average; "
      "control: off, the frame without occluders)" % (differ.sum(), darker))

# Moving the lines: an opacity edit.
scene.actors[0].SetPosition(0, 3, -2)
scene.frame()
report = scene.report()
edit = [r for r in report["reasons"] if "opacity changed" in r]
check(len(edit) == 1 and 0 < report["recomputed_voxels"] < voxels,
      "moving the lines is an opacity edit (%s; %d of %d voxels)" % (edit, report["recomputed_voxels"], voxels))
# A camera turn and a colour change: nothing recomputed.
scene.renderer.GetActiveCamera().Azimuth(15)
scene.frame()
turned = scene.report()
scene.actors[0].GetProperty().SetColor(0.9, 0.2, 0.2)
scene.frame()
coloured = scene.report()
check(turned["recomputed_voxels"] == 0 and coloured["recomputed_voxels"] == 0 and
      not any("opacity" in r for r in turned["reasons"] + coloured["reasons"]),
      "a camera turn and a colour change of the lines recompute nothing (%s; %s)"
      % (turned["reasons"], coloured["reasons"]))
# Hiding the lines removes them; the property off empties the list.
scene.actors[0].VisibilityOff()
scene.frame()
check(scene.mapper.GetNumberOfOccluders() == 1, "the lines hidden: the ball alone occludes (%d)"
      % scene.mapper.GetNumberOfOccluders())
scene.aoPass.SetGeometryOccludesVolumeAO(False)
scene.frame()
check(scene.mapper.GetNumberOfOccluders() == 0, "off again: the pass empties the list it set")

# An emptied list is the pass's to fill again; a volume taken out of the
# renderer keeps none of the pass's occluders.
again = Scene(wired=True)
again.frame()
again.mapper.RemoveAllOccluders()
again.frame()
refilled = again.mapper.GetNumberOfOccluders()
volume = again.renderer.GetVolumes().GetItemAsObject(0)
again.renderer.RemoveVolume(volume)
again.frame()
check(refilled == 2 and again.mapper.GetNumberOfOccluders() == 0,
      "an emptied list is filled again (%d); a volume taken out of the renderer keeps none (%d)"
      % (refilled, again.mapper.GetNumberOfOccluders()))

# The application's own occluder stays.
own = Scene(wired=False)
own.mapper.AddOccluder(own.actors[1])
own.aoPass.SetGeometryOccludesVolumeAO(True)
own.frame()
check(own.mapper.GetNumberOfOccluders() == 1,
      "a mapper given its own occluder keeps it (%d occluder)" % own.mapper.GetNumberOfOccluders())

if failures:
    print("%d check(s) failed" % len(failures))
    sys.exit(1)
print("all checks passed")

"""The clip widget dragged with real window-system events (a startup script
for test-gui-drag.sh, which drives the mouse with xdotool under Xvfb).

ParaView at its default settings (Depth Peeling For Volumes on), HeadMR as a
"Contextual AO Volume" with a Clip Shape Sphere, and a translucent sphere
(Opacity 0.4) over part of the volume, so that VTK draws the volume inside
its dual depth peeling in every frame; the box widget's face also turns
translucent while it is dragged.

This script sets the scene up and returns to the GUI's event loop. It
writes, to CAO_RESULT.targets, the view's display coordinates of the
widget's centre handle and of a point on its front face away from the
handles, and appends to CAO_RESULT.events one JSON line per event:
- "move": a mouse move the view's interactor received (its position), so
  the driver can map screen to view coordinates;
- "frame": each frame the mapper drew (time, its report's depth-peeling
  stage and stages, the clip pose the widget shows and whether the
  mapper's clip matrix is that pose);
- "error": any error the mapper reported.
Connected to a pvserver (test-gui-drag.sh with CAO_SERVER_URL set: a trial,
docs/interaction.md), the server draws and each frame's report is read
from it (the representation's FrameReport: a gather from the server at
each frame the GUI draws, within the timed drag); the mapper's errors are
then in the server's log, and "follows" reads the GUI's own mapper, which
is given the same pose but draws nothing."""
import json
import os
import time

from paraview.simple import *  # noqa: F401,F403

from clip_widget_pose import expected_matrix, matrix_list, to_display

base = os.environ["CAO_RESULT"]
# Appending (O_APPEND): the driver appends its own lines to the same file.
log = open(base + ".events", "a", buffering=1)


def emit(kind, **fields):
    fields["kind"] = kind
    fields["t"] = time.time()
    log.write(json.dumps(fields) + "\n")


LoadPlugin(os.environ["CAO_PLUGIN"], remote=False, ns=globals())
import contextualao  # noqa: E402,F401  (wraps vtkContextualAOVolumeMapper)
from paraview import servermanager  # noqa: E402

# Connected to a pvserver (CAO_SERVER_URL): the server draws (remote
# rendering); each frame's report is read from it (FrameReport).
REMOTE = servermanager.ActiveConnection.IsRemote()
if REMOTE:
    LoadPlugin(os.environ["CAO_PLUGIN"], remote=True, ns=globals())

reader = OpenDataFile(os.path.join(os.environ["CAO_DATA_DIR"], "HeadMRVolume.mhd"))
view = GetActiveViewOrCreate("RenderView")
if REMOTE:
    view.RemoteRenderThreshold = 0
display = Show(reader, view)
ColorBy(display, ("POINTS", "MetaImage"))
display.SetRepresentationType("Contextual AO Volume")
display.ClipShape = "Sphere"
b = reader.GetDataInformation().GetBounds()
centre = [0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5])]
size = max(b[1] - b[0], b[3] - b[2], b[5] - b[4])
ball = Sphere(Center=[centre[0] - 0.25 * size, centre[1] + 0.2 * size, b[5] + 0.05 * size],
              Radius=0.18 * size, ThetaResolution=32, PhiResolution=16)
ballDisplay = Show(ball, view)
ballDisplay.Opacity = 0.4
SetActiveSource(reader)
view.ResetCamera()
# An oblique view: the widget's handles then stand apart on the screen (head
# on, the front face's handle hides the centre handle).
camera = GetActiveCamera()
camera.Azimuth(30.0)
camera.Elevation(20.0)
view.ResetCamera()
Render(view)

mapper = display.GetClientSideObject().GetActiveRepresentation().GetActor().GetMapper()


def last_report():
    """The last frame's report: the client's mapper's, or the server's first process's."""
    if not REMOTE:
        return json.loads(mapper.GetLastFrameReport() or "{}")
    display.UpdatePropertyInformation()
    text = display.GetProperty("FrameReport").GetData()
    return json.loads((text[0] if isinstance(text, (list, tuple)) else text) or "{}")


def frame_count():
    return last_report().get("frame", 0) if REMOTE else mapper.GetFrameCount()


frames = [frame_count()]


def on_error(obj, event):
    emit("error", cls=obj.GetClassName())


def on_frame(obj, event):
    report = last_report() if REMOTE else None  # (remote: the count is the report's)
    count = report.get("frame", 0) if REMOTE else mapper.GetFrameCount()
    if count == frames[0]:
        return
    frames[0] = count
    report = report if REMOTE else last_report()
    actual = matrix_list(mapper.GetClipShape().GetMatrix())
    follows = max(abs(a - e) for a, e in zip(actual, expected_matrix(display))) < 1e-9
    emit("frame", count=count, peel=report.get("depth_peeling", "?"),
         sample_distance=report.get("sample_distance"), reasons=report.get("reasons", []),
         image_sample_distance=report.get("image_sample_distance"),
         interactive=report.get("interactive"), redrawn=report.get("redrawn"),
         ms={s["name"]: s["ms"] for s in report.get("stages", []) if s["name"] != "raycast"},
         raycast_ms=sum(s["ms"] for s in report.get("stages", []) if s["name"] == "raycast"),
         stages=[s["name"] for s in report.get("stages", [])],
         position=list(display.ClipPosition), rotation=list(display.ClipOrientation),
         scale=list(display.ClipScale),
         follows=follows)


def on_move(obj, event):
    x, y = obj.GetEventPosition()
    emit("move", x=x, y=y, size=list(obj.GetRenderWindow().GetSize()))


errorTag = mapper.AddObserver("ErrorEvent", on_error)
frameTag = view.GetRenderWindow().AddObserver("EndEvent", on_frame)
# A render under way (started, not ended) keeps the driver waiting: a still
# frame of a large volume on a software rasteriser takes longer than the
# driver's 3 s of quiet.
startTag = view.GetRenderWindow().AddObserver("StartEvent", lambda obj, event: emit("start"))
moveTag = view.GetRenderWindow().GetInteractor().AddObserver("MouseMoveEvent", on_move)

# The widget's box is the unit shape's box under its pose: its centre
# handle, and on its +z face (it faces the camera) a point halfway between
# the face's centre and its +x edge, away from the face's handle.
pose = expected_matrix(display)


def box_point(u):
    return [sum(pose[4 * r + c] * (list(u) + [1.0])[c] for c in range(4)) for r in range(3)]


# One interactive frame before the drags, as a user's first look around
# would draw: on a software rasteriser its programs (the interactive ray
# cast's and the upsampling's) compile for seconds, on a server longer
# (Plugin.GUI.ClipDragRemote once saw no frame at all during the first
# drag while they compiled, and the GUI logged nothing, so the driver's
# wait for quiet ended early).
view.SMProxy.InteractiveRender()
view.SMProxy.StillRender()

targets = {"centre": to_display(view, box_point([0, 0, 0])),
           "face": to_display(view, box_point([0.5, 0, 1])),
           "size": list(view.GetRenderWindow().GetSize()),
           # The centre handle 80 pixels right; the face 70 up, pressed
           # where the first drag left it (80 pixels right of the target:
           # on a box less than about 160 pixels wide on the screen the
           # target itself is off the moved box, and the drag turned
           # nothing); the middle button moves the box from anywhere on it,
           # whatever the view (head on, the front face's handle covers the
           # centre handle): over the box's centre where the first drag
           # left it (80 pixels right of the target; the face drag turned
           # the box about its centre), 60 pixels down.
           "drags": [["centre", "centre", 0, 0, 80, 0, 1], ["face", "face", 80, 0, 0, -70, 1],
                     ["middle", "centre", 80, 0, 0, 60, 2]],
           "depth_peeling_for_volumes": int(view.DepthPeelingForVolumes)}
with open(base + ".targets", "w") as f:
    json.dump(targets, f)

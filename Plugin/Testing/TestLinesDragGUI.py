"""The camera zoomed over streamlines with real window-system events (a
startup script for test-gui-drag.sh, which drives the mouse with xdotool
under Xvfb), in the Render View (Contextual AO) at ParaView's defaults
(Surface AO Backend CPU, so that the run is the same on any machine).

carotid.vtk's Stream Tracer (150 seeds) drawn as lines 2 pixels wide. The
driver presses 50 pixels above the middle of the view and drags 100 pixels
down with the right button (ParaView's zoom: the camera dollies, and lines
drawn a fixed number of pixels wide change their width in the world, so a
still frame voxelizes them again) for about 2.5 s, then waits until the GUI
draws no more; the checks are on that drag. Before it the driver makes the
same drag once ("warmup"): under Xvfb with xdotool the GUI's first drag in
the view (after the driver's focus click) reaches the interactor style,
which starts an interaction and draws frames, but no mouse move reaches
the interactor and the camera does not move, with any button and in
ParaView's own Render View as well (seen, not explained); from the second
drag on the camera follows the mouse. This script writes the view's middle and size to
CAO_RESULT.targets and appends one JSON line per event to CAO_RESULT.events:
"move" (the interactor's mouse moves, for the driver to find the view) and
"frame" (each frame: the renderer's camera position, the pass's report's
lines section and error). gui-lines-drag-check.py checks the log."""
import json
import os
import time

from paraview.simple import *  # noqa: F401,F403

from gui_scene import carotid_streamlines, contextual_ao_view

base = os.environ["CAO_RESULT"]
log = open(base + ".events", "a", buffering=1)


def emit(kind, **fields):
    fields["kind"] = kind
    fields["t"] = time.time()
    log.write(json.dumps(fields) + "\n")


LoadPlugin(os.environ["CAO_PLUGIN"], remote=False, ns=globals())
import contextualao  # noqa: E402,F401  (wraps vtkContextualAOPass)

view, layout = contextual_ao_view()
view.SurfaceAOBackend = "CPU"
carotid_streamlines(view)
view.CameraPosition = [137.5, 40.0, 70.0]
view.CameraFocalPoint = [137.5, 104.0, 20.0]
view.CameraViewUp = [0.0, 0.0, 1.0]
view.ResetCamera()
Render(view)

chain = view.GetRenderer().GetPass()
while chain is not None and chain.GetClassName() != "vtkContextualAOPass":
    chain = chain.GetDelegatePass() if hasattr(chain, "GetDelegatePass") else None
frames = [chain.GetFrameCount() if chain else 0]


def on_frame(obj, event):
    count = chain.GetFrameCount()
    if count == frames[0]:
        return
    frames[0] = count
    report = json.loads(chain.GetLastFrameReport() or "{}")
    emit("frame", count=count, camera=list(view.GetRenderer().GetActiveCamera().GetPosition()),
         interactive=bool(chain.GetInteractiveFrames()), lines=report.get("lines", {}),
         error=report.get("error"), stages=report.get("stages", {}))


def on_move(obj, event):
    x, y = obj.GetEventPosition()
    emit("move", x=x, y=y, size=list(obj.GetRenderWindow().GetSize()))


frameTag = view.GetRenderWindow().AddObserver("EndEvent", on_frame)
# A render under way (started, not ended) keeps the driver waiting: a still
# frame of a large volume on a software rasteriser takes longer than the
# driver's 3 s of quiet.
startTag = view.GetRenderWindow().AddObserver("StartEvent", lambda obj, event: emit("start"))
moveTag = view.GetRenderWindow().GetInteractor().AddObserver("MouseMoveEvent", on_move)
size = list(view.GetRenderWindow().GetSize())
with open(base + ".targets", "w") as f:
    json.dump({"middle": [size[0] / 2.0, size[1] / 2.0], "size": size, "found": chain is not None,
               "drags": [["warmup", "middle", 0, -50, 0, 100, 3], ["zoom", "middle", 0, -50, 0, 100, 3]]}, f)

"""The clip shape's widget in the ParaView GUI (a startup script under
Xvfb): the "Contextual AO Volume" representation shows a sphere widget at
the clip shape (its position and size); dragging its centre with the mouse
(events sent to the view's interactor, as a user's drag) moves Clip
Position, the GUI applies it at once, and the mapper's clip shape follows
with frames drawn during the drag.
Negative control: the same drag started far from the widget moves nothing.
Writes CAO_RESULT (ok/FAIL lines, then PASSED or FAILED)."""
import os

from paraview.simple import *  # noqa: F401,F403

out = open(os.environ["CAO_RESULT"], "w")
failures = []


def check(ok, what):
    out.write(("ok: " if ok else "FAIL: ") + what + "\n")
    if not ok:
        failures.append(what)


def drag(view, x, y, dx):
    iren = view.GetRenderWindow().GetInteractor()
    iren.SetEventInformation(int(x), int(y), 0, 0)
    iren.InvokeEvent("MouseMoveEvent")
    iren.InvokeEvent("LeftButtonPressEvent")
    for k in range(1, 11):
        iren.SetEventInformation(int(x + dx * k / 10.0), int(y), 0, 0)
        iren.InvokeEvent("MouseMoveEvent")
    iren.InvokeEvent("LeftButtonReleaseEvent")


try:
    LoadPlugin(os.environ["CAO_PLUGIN"], remote=False, ns=globals())
    import contextualao  # noqa: F401  (wraps vtkContextualAOVolumeMapper)
    reader = OpenDataFile(os.path.join(os.environ["CAO_DATA_DIR"], "HeadMRVolume.mhd"))
    view = GetActiveViewOrCreate("RenderView")
    display = Show(reader, view)
    ColorBy(display, ("POINTS", "MetaImage"))
    display.SetRepresentationType("Contextual AO Volume")
    display.ClipShape = "Sphere"
    SetActiveSource(reader)
    view.ResetCamera()
    Render(view)
    mapper = display.GetClientSideObject().GetActiveRepresentation().GetActor().GetMapper()
    start = list(display.ClipPosition)
    renderer = view.GetRenderer()
    renderer.SetWorldPoint(start[0], start[1], start[2], 1.0)
    renderer.WorldToDisplay()
    x, y, _ = renderer.GetDisplayPoint()
    # Negative control: a drag in the view's corner, far from the widget.
    drag(view, 5, 5, 60)
    Render(view)
    check(list(display.ClipPosition) == start,
          "a drag away from the widget leaves Clip Position %s (%s)" % (start, list(display.ClipPosition)))
    frames = mapper.GetFrameCount()
    drag(view, x, y, 60)
    Render(view)
    moved = list(display.ClipPosition)
    check(moved[0] > start[0] + 10.0 and abs(moved[1] - start[1]) < 1e-6,
          "dragging the widget's centre right moves Clip Position along +x: %s -> %s" % (start, moved))
    # The GUI applies display properties at once and renders while the
    # widget moves: the mapper's clip prop is at the new position and frames
    # were drawn during the drag (each recomputing the voxels the move affects).
    check(list(mapper.GetClipShape().GetPosition()) == moved and mapper.GetFrameCount() > frames,
          "the mapper's clip shape follows the widget (%s) and %d frames were drawn during the drag"
          % (list(mapper.GetClipShape().GetPosition()), mapper.GetFrameCount() - frames))
    SaveScreenshot(os.environ["CAO_RESULT"] + ".png", view, ImageResolution=[400, 300])
except Exception as e:  # noqa: BLE001  (reported as a failure)
    check(False, "exception: %r" % (e,))
finally:
    out.write("PASSED\n" if not failures else "FAILED\n")
    out.close()
    os._exit(0)

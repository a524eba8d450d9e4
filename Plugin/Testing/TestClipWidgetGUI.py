"""The clip shape's widget in the ParaView GUI (a startup script under
Xvfb): the "Contextual AO Volume" representation shows ParaView's box widget
around the clip shape. With the mouse (events sent to the view's
interactor, as a user's drag):
- dragging the box's centre handle moves Clip Position, the GUI applies it
  at once, and the mapper's clip shape follows with frames drawn during the
  drag;
- dragging across a face of the box turns it: Clip Rotation changes and the
  mapper's clip matrix is the box widget's pose (the shape stays inscribed
  in the box the user sees).
Negative control: the same drags started far from the widget change
nothing.
Writes CAO_RESULT (ok/FAIL lines, then PASSED or FAILED)."""
import os

from paraview.simple import *  # noqa: F401,F403

from gui_scene import Result

from clip_widget_pose import expected_matrix, matrix_list, to_display

result = Result()
check = result.check


def drag(view, x, y, dx, dy=0):
    iren = view.GetRenderWindow().GetInteractor()
    iren.SetEventInformation(int(x), int(y), 0, 0)
    iren.InvokeEvent("MouseMoveEvent")
    iren.InvokeEvent("LeftButtonPressEvent")
    for k in range(1, 11):
        iren.SetEventInformation(int(x + dx * k / 10.0), int(y + dy * k / 10.0), 0, 0)
        iren.InvokeEvent("MouseMoveEvent")
    iren.InvokeEvent("LeftButtonReleaseEvent")


def box_shown(view):
    """Whether a visible box widget representation is in the view's renderers."""
    renderers = view.GetRenderWindow().GetRenderers()
    renderers.InitTraversal()
    for _ in range(renderers.GetNumberOfItems()):
        props = renderers.GetNextItem().GetViewProps()
        props.InitTraversal()
        for _ in range(props.GetNumberOfItems()):
            prop = props.GetNextProp()
            if prop.IsA("vtkWidgetRepresentation") and "Box" in prop.GetClassName() and prop.GetVisibility():
                return True
    return False


def reselect(source):
    """The panel as a user finds it after a change made from Python: the
    representation's panel made again (its decorators re-read the
    properties when the source is selected)."""
    SetActiveSource(None)
    SetActiveSource(source)


def shape_matrix(mapper):
    return matrix_list(mapper.GetClipShape().GetMatrix())


try:
    LoadPlugin(os.environ["CAO_PLUGIN"], remote=False, ns=globals())
    import contextualao  # noqa: F401  (wraps vtkContextualAOVolumeMapper)
    reader = OpenDataFile(os.path.join(os.environ["CAO_DATA_DIR"], "HeadMRVolume.mhd"))
    view = GetActiveViewOrCreate("RenderView")
    display = Show(reader, view)
    ColorBy(display, ("POINTS", "MetaImage"))
    display.SetRepresentationType("Contextual AO Volume")
    display.ClipShape = "Sphere"
    b = reader.GetDataInformation().GetBounds()
    display.ClipPosition = [0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5])]
    SetActiveSource(reader)
    reselect(reader)
    view.ResetCamera()
    mapper = display.GetClientSideObject().GetActiveRepresentation().GetActor().GetMapper()
    errors = []
    mapper.AddObserver("ErrorEvent", lambda obj, event: errors.append(obj.GetClassName()))
    Render(view)
    # The first frame precomputes the LAO, whose ProgressEvents the GUI
    # answers by painting its other widgets: that frame is still drawn (it
    # once lost its context there and its ray cast failed).
    check(mapper.GetFrameCount() >= 1 and not errors,
          "the first frame, through the GUI's progress, precomputes and is drawn (%d frame(s), %d mapper "
          "error(s))" % (mapper.GetFrameCount(), len(errors)))
    start = list(display.ClipPosition)
    x, y = to_display(view, start)
    # Negative control: drags in the view's corner, far from the widget.
    drag(view, 5, 5, 60)
    drag(view, 5, 5, 0, 60)
    Render(view)
    check(list(display.ClipPosition) == start and list(display.ClipOrientation) == [0, 0, 0],
          "drags away from the widget leave Clip Position %s and Clip Rotation (%s, %s)"
          % (start, list(display.ClipPosition), list(display.ClipOrientation)))
    frames = mapper.GetFrameCount()
    drag(view, x, y, 60)
    Render(view)
    moved = list(display.ClipPosition)
    check(moved[0] > start[0] + 10.0 and abs(moved[1] - start[1]) < 1e-6,
          "dragging the box's centre handle right moves Clip Position along +x: %s -> %s" % (start, moved))
    # The GUI applies display properties at once and renders while the
    # widget moves: the mapper's clip prop is at the new pose and frames
    # were drawn during the drag (each recomputing the voxels the move affects).
    check(max(abs(a - b) for a, b in zip(shape_matrix(mapper), expected_matrix(display))) < 1e-9
          and mapper.GetFrameCount() > frames,
          "the mapper's clip shape follows the widget (translation %s) and %d frames were drawn "
          "during the drag" % (shape_matrix(mapper)[3::4][:3], mapper.GetFrameCount() - frames))
    # Turn the box: press on its front face (the view looks down -z, the
    # face nearest the camera), halfway between the centre and the face's
    # right edge (away from the face's handle), and drag upwards.
    scale = list(display.ClipScale)
    face = [moved[0] + 0.5 * scale[0], moved[1], moved[2] + scale[2]]
    fx, fy = to_display(view, face)
    frames = mapper.GetFrameCount()
    drag(view, fx, fy, 0, 60)
    Render(view)
    turned = list(display.ClipOrientation)
    check(max(abs(v) for v in turned) > 5.0,
          "dragging across the box's face turns it: Clip Rotation %s" % (turned,))
    check(max(abs(a - b) for a, b in zip(shape_matrix(mapper), expected_matrix(display))) < 1e-9
          and mapper.GetFrameCount() > frames,
          "the mapper's clip matrix is the turned box's pose and %d frames were drawn during the turn"
          % (mapper.GetFrameCount() - frames))
    SaveScreenshot(os.environ["CAO_RESULT"] + ".png", view, ImageResolution=[400, 300])
    check(not errors, "no mapper error in any frame (%d)" % len(errors))
    # Clip Shape None: no box in the view (nor in screenshots), and a drag
    # where its centre handle was moves nothing. Positive control: the box
    # is there while a shape clips.
    shown = box_shown(view)
    display.ClipShape = "None"
    reselect(reader)
    Render(view)
    hidden = not box_shown(view)
    before = list(display.ClipPosition)
    x, y = to_display(view, before)
    drag(view, x, y, 60)
    Render(view)
    check(shown and hidden and list(display.ClipPosition) == before,
          "the box widget is shown while a shape clips (%s), hidden at Clip Shape None (%s), and a drag "
          "there leaves Clip Position %s (%s)" % (shown, hidden, before, list(display.ClipPosition)))
    display.ClipShape = "Sphere"
    reselect(reader)
    Render(view)
    check(box_shown(view), "the box comes back with a shape")
    # The volume hidden (the eye in the Pipeline Browser): no box over the
    # empty view; shown again, the box is back. (Control: the box shown
    # just above, with the same shape.)
    Hide(reader, view)
    reselect(reader)
    Render(view)
    gone = not box_shown(view)
    Show(reader, view)
    reselect(reader)
    Render(view)
    check(gone and box_shown(view), "the box is hidden with the volume (%s) and back with it" % gone)
    # Drawn as another representation (Outline): no box, the clip being
    # this one's; back to Contextual AO Volume, the box is back. (Control:
    # the box shown just above.)
    display.SetRepresentationType("Outline")
    reselect(reader)
    Render(view)
    other = not box_shown(view)
    display.SetRepresentationType("Contextual AO Volume")
    reselect(reader)
    Render(view)
    check(other and box_shown(view), "the box is hidden as Outline (%s) and back as Contextual AO Volume" % other)
except Exception as e:  # noqa: BLE001  (reported as a failure)
    check(False, "exception: %r" % (e,))
finally:
    result.finish()

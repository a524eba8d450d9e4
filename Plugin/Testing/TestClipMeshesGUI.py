"""The Properties panel's clip meshes in the ParaView GUI (a startup script
under Xvfb, ParaView's default settings): one row per polygonal source of
the pipeline, each with a tick (it clips the volume) and its own named mode
(pqCAOClipMeshesWidget). The panel's widgets are read and used through
PyQt5 (Debian's python3-pyqt5, which .ci/setup.sh installs) from the GUI's
own QApplication; without PyQt5 the test skips (125).
- A Wavelet volume as "Contextual AO Volume", a Sphere and a Box: two rows,
  Sphere1 and Box1 (not the Wavelet: it is an image), none ticked, their
  modes disabled.
- Ticking Sphere1 sets Clip Meshes to it with the mode "As Clip Mode", and
  the mapper holds one clip shape; ticking Box1 too and picking Probing in
  its row gives [Sphere1, Box1] and [As Clip Mode, Probing], and the
  mapper two shapes.
- Edit > Undo ("Undo Change Clip Meshes") unticks it and the view is
  redrawn without the clip; Redo ticks it again (negative control, by
  hand: without the widget's own undo step the action read "Undo Changed
  'vtkSMCAOVolumeRepresentationProxy'" and the first undo check failed).
- A change from Python (Box1 alone, Subtraction) shows in the rows.
- A source added and applied gets a row; deleted, its row goes; a ticked
  one deleted leaves the volume's display in place.
- The group is hidden with the representation Outline.
- The clip box's group (pqCAOClipBoxWidget) shows Position, Rotation,
  Scale and Reset Using Data Bounds, and not the reference bounds' fields
  and tick (negative control, run: ParaView's InteractiveBox shows them).
Negative control: before this widget the panel had one input selector and
a bare list of numbers (the table is not found: the first check fails).
Writes CAO_RESULT (ok/FAIL lines, then PASSED, FAILED or SKIPPED)."""
import os
import time

from gui_scene import Result, pyqt5

result = Result()
check = result.check
QtCore, _, QtWidgets = pyqt5(result, "to read and use the Properties panel's widgets")

try:
    from paraview.simple import *  # noqa: F401,F403
    LoadPlugin(os.environ["CAO_PLUGIN"], remote=False, ns=globals())
    import contextualao  # noqa: F401  (wraps vtkContextualAOVolumeMapper)
    app = QtWidgets.QApplication.instance()
    view = GetActiveViewOrCreate("RenderView")
    volume = Wavelet(WholeExtent=[-16, 16, -16, 16, -16, 16])
    display = Show(volume, view)
    ColorBy(display, ("POINTS", "RTData"))
    display.SetRepresentationType("Contextual AO Volume")
    display.ClipShape = "None"
    sphere = Sphere(Center=[0.0, 0.0, 8.0], Radius=9.0, ThetaResolution=32, PhiResolution=32)
    box = Box(Center=[0.0, 0.0, -8.0], XLength=14.0, YLength=14.0, ZLength=14.0)
    for source in (sphere, box):
        source.UpdatePipeline()
    SetActiveSource(None)
    SetActiveSource(volume)  # the panel as a user finds it with the volume selected
    view.ResetCamera()
    Render(view)
    mapper = display.GetClientSideObject().GetActiveRepresentation().GetActor().GetMapper()

    def settle():
        for _ in range(3):
            app.processEvents()
            QtCore.QCoreApplication.sendPostedEvents()

    def table():
        settle()
        found = [w for w in app.allWidgets() if w.objectName() == "ClipMeshesTable"]
        return found[0] if len(found) == 1 else None

    def rows():
        t = table()
        if t is None:
            return None
        return [(t.item(r, 0).text(), t.item(r, 0).checkState() == QtCore.Qt.Checked,
                 t.cellWidget(r, 1).currentText(), t.cellWidget(r, 1).isEnabled()) for r in range(t.rowCount())]

    def row_of(name):
        t = table()
        return [r for r in range(t.rowCount()) if t.item(r, 0).text() == name][0]

    t = table()
    check(t is not None and t.isVisible(), "the panel has the clip meshes' table, shown (%s)" % t)
    if t is None:
        result.finish()
    check(rows() == [("Sphere1", False, "As Clip Mode", False), ("Box1", False, "As Clip Mode", False)],
          "one row per polygonal source, none ticked, modes disabled: %s" % rows())
    check(t.horizontalHeaderItem(0).text() == "Clip with" and t.horizontalHeaderItem(1).text() == "Mode",
          "the columns are named (Clip with, Mode)")

    t.item(row_of("Sphere1"), 0).setCheckState(QtCore.Qt.Checked)
    settle()
    Render(view)
    check(list(display.ClipMeshes) == [sphere] and list(display.ClipMeshModes) == ["As Clip Mode"],
          "ticking Sphere1: Clip Meshes [Sphere1], modes %s" % list(display.ClipMeshModes))
    check(mapper.GetNumberOfClipShapes() == 1, "the mapper holds 1 shape (%d)" % mapper.GetNumberOfClipShapes())
    check(rows()[row_of("Sphere1")][3], "Sphere1's mode is enabled once ticked")

    # Edit > Undo and Redo, as the GUI's own actions: one step named for the
    # change; the undo stack's render draws the restored clip (no other
    # property change needed), and the rows follow.
    actions = {}
    for w in app.topLevelWidgets():
        actions.update({a.objectName(): a for a in w.findChildren(QtWidgets.QAction)
                        if a.objectName() in ("actionEditUndo", "actionEditRedo")})
    renders = []
    observer = view.GetRenderWindow().AddObserver("EndEvent", lambda obj, event: renders.append(1))

    def edit(name):
        del renders[:]
        actions[name].trigger()
        for _ in range(50):  # (the view renders on a timer)
            settle()
            if renders:
                break
            time.sleep(0.02)

    check("actionEditUndo" in actions and actions["actionEditUndo"].text() == "&Undo Change Clip Meshes",
          "Edit > Undo names the change: %s" % (actions["actionEditUndo"].text() if "actionEditUndo" in actions
                                                 else "no undo action"))
    edit("actionEditUndo")
    check(list(display.ClipMeshes) == [] and mapper.GetNumberOfClipShapes() == 0 and renders
          and not rows()[row_of("Sphere1")][1],
          "Undo: no clip mesh, the view redrawn with none (%d shapes), the row unticked: %s"
          % (mapper.GetNumberOfClipShapes(), rows()))
    edit("actionEditRedo")
    check(list(display.ClipMeshes) == [sphere] and mapper.GetNumberOfClipShapes() == 1 and renders
          and rows()[row_of("Sphere1")][1],
          "Redo: Sphere1 clips again (%d shape), the row ticked: %s" % (mapper.GetNumberOfClipShapes(), rows()))
    view.GetRenderWindow().RemoveObserver(observer)

    t.item(row_of("Box1"), 0).setCheckState(QtCore.Qt.Checked)
    settle()
    t.cellWidget(row_of("Box1"), 1).setCurrentIndex(2)
    settle()
    Render(view)
    check(list(display.ClipMeshes) == [sphere, box] and list(display.ClipMeshModes) == ["As Clip Mode", "Probing"],
          "ticking Box1, Probing: Clip Meshes [Sphere1, Box1], modes %s" % list(display.ClipMeshModes))
    check(mapper.GetNumberOfClipShapes() == 2, "the mapper holds 2 shapes (%d)" % mapper.GetNumberOfClipShapes())

    display.ClipMeshes = [box]
    display.ClipMeshModes = ["Subtraction"]
    check(rows() == [("Sphere1", False, "As Clip Mode", False), ("Box1", True, "Subtraction", True)],
          "a change from Python shows in the rows: %s" % rows())
    Render(view)
    check(mapper.GetNumberOfClipShapes() == 1, "from Python: the mapper holds 1 shape (%d)"
          % mapper.GetNumberOfClipShapes())

    cone = Cone()
    cone.UpdatePipeline()
    SetActiveSource(volume)
    check([r[0] for r in rows()] == ["Sphere1", "Box1", "Cone1"], "a new source gets a row: %s" % rows())
    Delete(cone)
    del cone
    SetActiveSource(volume)
    check([r[0] for r in rows()] == ["Sphere1", "Box1"], "a deleted source's row goes: %s" % rows())

    # A ticked mesh deleted: the volume's display stays (ParaView deleted it
    # with the mesh before), and its row goes.
    Delete(box)
    del box
    SetActiveSource(volume)
    kept = GetDisplayProperties(volume, view)
    check(kept.SMProxy is display.SMProxy and kept.Representation == "Contextual AO Volume"
          and list(display.ClipMeshes) == [] and [r[0] for r in rows()] == ["Sphere1"],
          "deleting the ticked Box1 keeps the display and drops its row: %s" % rows())

    display.SetRepresentationType("Outline")
    settle()
    check(not table().isVisible(), "hidden with the representation Outline")
    display.SetRepresentationType("Contextual AO Volume")
    SetActiveSource(None)
    SetActiveSource(volume)
    check(table().isVisible(), "shown again as Contextual AO Volume")

    # The clip box's group: ParaView's box widget (Position, Rotation,
    # Scale, Reset Using Data Bounds) without the reference bounds' six
    # fields and tick, which ParaView's own InteractiveBox shows to every
    # user (the representation poses the shapes in [-1,1]^3).
    display.ClipShape = "Sphere"
    SetActiveSource(None)
    SetActiveSource(volume)
    settle()

    def shown(name):
        # (the one in a shown box group: the panel keeps hidden ones of
        # other proxies)
        found = [w for w in app.allWidgets() if w.objectName() == name and w.parentWidget() is not None
                 and w.parentWidget().isVisible()]
        return len(found) == 1 and found[0].isVisible()

    box_fields = {n: shown(n) for n in ("translateX", "rotateX", "scaleX", "resetBounds",
                                         "useReferenceBounds", "xmin", "zmax")}
    check(all(box_fields[n] for n in ("translateX", "rotateX", "scaleX", "resetBounds")) and
          not any(box_fields[n] for n in ("useReferenceBounds", "xmin", "zmax")),
          "the clip box's group shows the pose and Reset Using Data Bounds, not the reference "
          "bounds: %s" % box_fields)
except Exception:  # noqa: BLE001  (reported in the result)
    import traceback
    check(False, "the script ran: %s" % traceback.format_exc())
result.finish()

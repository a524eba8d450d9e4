"""A mouse button held over the render view makes the still frames the
volume's mapper draws interactive (InteractiveWhileDragging: ParaView asks
for still frames during a widget drag), in the process that draws: the GUI's
own (Plugin.GUI.PointerHeld) or, with the GUI connected to a pvserver on 2
processes that draws (remote rendering), the server's
(Plugin.GUI.PointerHeldRemote), where the flag the GUI sets in its own
process does not reach: the GUI's pointer tracker sends the press and the
release to the server (vtkSMCAOVolumeRepresentationProxy::PushPointerHeld).
The frames' reports are read through the representation's FrameReport
information property (the server's first process's when remote).

Checks: a still frame before the press is still; a still frame asked for
with the button held (pressed on the view's container widget, no move: no
VTK interaction starts) is drawn as an interactive one for that reason
("interactive: a pointer button is held"); after the release the tracker
renders once more, a still frame. Negative controls: with the tracker's
calls to the server removed, the remote run's held frame was still (its
check failed) while the builtin run passed; with no render after a remote
release, the remote run's last check failed. The GUI's log must hold no
GL-state error (test-gui-script.sh).
Writes CAO_RESULT (ok/FAIL lines, then PASSED, FAILED or SKIPPED)."""
import json
import os
import time

from gui_scene import Result, pyqt5

result = Result()
check = result.check
QtCore, QtGui, QtWidgets = pyqt5(result, "to send the mouse events to the view's widget")

HELD = "interactive: a pointer button is held"

try:
    from paraview.simple import *  # noqa: F401,F403
    from paraview import servermanager
    LoadPlugin(os.environ["CAO_PLUGIN"], remote=False, ns=globals())
    remote = servermanager.ActiveConnection.IsRemote()
    if remote:
        LoadPlugin(os.environ["CAO_PLUGIN"], remote=True, ns=globals())
    check(remote == ("CAO_SERVER_URL" in os.environ), "connected as started (remote: %s)" % remote)
    app = QtWidgets.QApplication.instance()
    view = GetActiveViewOrCreate("RenderView")
    if remote:
        view.RemoteRenderThreshold = 0  # the server draws
    source = Wavelet(WholeExtent=[-20, 20, -20, 20, -20, 20])
    display = Show(source, view)
    display.Representation = "Contextual AO Volume"
    display.ClipShape = "Sphere"
    Render(view)

    def report():
        display.UpdatePropertyInformation()
        text = display.GetProperty("FrameReport").GetData()
        text = text[0] if isinstance(text, (list, tuple)) else text
        try:
            return json.loads(text)
        except (TypeError, ValueError):
            return None

    def settle(seconds=1.0):
        end = time.time() + seconds
        while time.time() < end:
            app.processEvents()
            time.sleep(0.02)

    def frame_string(r):
        return "frame %s, interactive %s, reasons %s" % (
            r.get("frame"), r.get("interactive"), r.get("reasons")) if r else "no report"

    still = report()
    check(still is not None and still.get("interactive") is False and HELD not in still.get("reasons", []),
          "a still frame before the press: %s" % frame_string(still))

    # The view's container (pqQVTKWidget), not the VTK widget inside it:
    # the tracker sees the press, VTK's interactor does not, so no
    # interaction starts and the frame after the release is the tracker's.
    widgets = [w for w in app.allWidgets() if w.inherits("pqQVTKWidget") and w.isVisible()]
    check(len(widgets) == 1, "the render view's widget is found (%d)" % len(widgets))
    widget = widgets[0]
    centre = QtCore.QPointF(widget.width() / 2.0, widget.height() / 2.0)

    def mouse(kind, buttons):
        event = QtGui.QMouseEvent(kind, centre, QtCore.Qt.LeftButton, buttons, QtCore.Qt.NoModifier)
        QtWidgets.QApplication.sendEvent(widget, event)

    mouse(QtCore.QEvent.MouseButtonPress, QtCore.Qt.LeftButton)
    settle(0.3)
    display.ClipPosition = [2.0, 1.0, 0.0]  # a drag's still frame (the widget sets a property)
    Render(view)
    settle(1.0)  # (and the render ParaView queued for the property, still held)
    held = report()
    check(held is not None and held.get("interactive") is True and HELD in held.get("reasons", []),
          "a still frame with the button held is drawn interactive: %s" % frame_string(held))

    mouse(QtCore.QEvent.MouseButtonRelease, QtCore.Qt.NoButton)
    settle(2.0)  # the tracker's render after the release (queued)
    after = report()
    check(after is not None and held is not None and after.get("frame", -1) > held.get("frame", -1)
          and after.get("interactive") is False and HELD not in after.get("reasons", []),
          "the release renders a still frame: %s" % frame_string(after))
except Exception as e:  # noqa: BLE001 (any failure is the test's)
    import traceback
    check(False, "the script raised: %s\n%s" % (e, traceback.format_exc()))
result.finish()

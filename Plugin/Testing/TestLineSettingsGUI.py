"""The view's line settings in the ParaView GUI's Properties panel (a
startup script under Xvfb, ParaView's default settings) are shown only
while the view draws lines: with a sphere alone, Line AO Method, Line AO Samples,
Line AO Slices and Line Shading are hidden (the Surface AO Radius beside
them shown: the widgets are found); with a Line source shown too, all four
are shown; Line AO Method None hides its three settings and keeps Line AO
Method; Surface AO Method None keeps the four and the Radius (the lines'
AO uses it), and with Line AO Method None too hides the Radius; the
line hidden again hides all four; after the view is closed, a new view
hides them until it draws the line. Plugin.GUI.LineSettingsRemote runs it
in a GUI connected to a pvserver on 2 processes, the server drawing
(remote rendering; the count gathered from the server as
vtkCAOLineActorsInformation; before that the settings stayed hidden with
the line shown, the view's information property being read from the
client's view). The panel's widgets are read through
PyQt5 (Debian's python3-pyqt5, which .ci/setup.sh installs) from the
GUI's own QApplication; without PyQt5 the test skips (125). Negative
control: before the CAOLinesInView decorator the four were shown with the
sphere alone (the first check failed).
Writes CAO_RESULT (ok/FAIL lines, then PASSED, FAILED or SKIPPED)."""
import os

from gui_scene import Result, contextual_ao_view, pyqt5

result = Result()
check = result.check
LINE_SETTINGS = ("LineAOMethod", "LineAOSamples", "LineAOSlices", "LineShading")
QtCore, _, QtWidgets = pyqt5(result, "to read the Properties panel's widgets")

try:
    from paraview.simple import *  # noqa: F401,F403
    from paraview import servermanager
    LoadPlugin(os.environ["CAO_PLUGIN"], remote=False, ns=globals())
    remote = servermanager.ActiveConnection.IsRemote()
    if remote:  # (Plugin.GUI.LineSettingsRemote: a pvserver on 2 processes)
        LoadPlugin(os.environ["CAO_PLUGIN"], remote=True, ns=globals())
    view, layout = contextual_ao_view()
    if remote:
        view.RemoteRenderThreshold = 0  # the server draws: the client's view holds no lines
    check(remote == ("CAO_SERVER_URL" in os.environ), "connected as started (remote: %s)" % remote)
    app = QtWidgets.QApplication.instance()

    def shown(name):
        """Whether the panel shows property NAME's widget (None: not one such widget)."""
        app.processEvents()
        widgets = [w for w in app.allWidgets() if w.objectName() == name and isinstance(w, QtWidgets.QFrame)]
        return widgets[0].isVisible() if len(widgets) == 1 else None

    def expect(scene, visible, radius=True):
        states = {name: shown(name) for name in LINE_SETTINGS + ("SurfaceAORadius",)}
        check(states["SurfaceAORadius"] is radius, "%s: Surface AO Radius is %s (%s)"
              % (scene, "shown" if radius else "hidden", states["SurfaceAORadius"]))
        for name in LINE_SETTINGS:
            check(states[name] is (name in visible),
                  "%s: %s is %s (widget shown: %s)" % (scene, name, "shown" if name in visible else "hidden",
                                                        states[name]))

    ball = Show(Sphere(), view)
    Render(view)
    expect("a sphere alone", ())
    line = Line(Point1=[-1.0, 0.0, 0.6], Point2=[1.0, 0.0, 0.6], Resolution=20)
    Show(line, view)
    Render(view)
    expect("a sphere and a line", LINE_SETTINGS)
    view.LineAOMethod = 0
    Render(view)
    expect("Line AO Method None", ("LineAOMethod",))
    view.LineAOMethod = 1
    # One technique per kind: Surface AO Method None keeps the lines' settings
    # and the Radius (the lines' too) while lines get AO, and hides the
    # Radius once neither kind does.
    view.SurfaceAOMethod = "None"
    Render(view)
    expect("Surface AO Method None with the line", LINE_SETTINGS)
    view.LineAOMethod = 0
    Render(view)
    expect("Surface and Line AO Method None", ("LineAOMethod",), radius=False)
    # (with no AO at all the pass still counts the lines the view draws)
    Hide(line, view)
    Render(view)
    expect("both None, the line hidden", (), radius=False)
    Show(line, view)
    Render(view)
    expect("both None, the line shown again", ("LineAOMethod",), radius=False)
    view.LineAOMethod = 1
    view.SurfaceAOMethod = "Voxel Cones"
    Hide(line, view)
    Render(view)
    expect("the line hidden", ())
    # A view closed (its panel and decorators go) and a new one: the old
    # decorators leave no observer behind, the new view starts hidden and
    # shows the settings once it draws the line.
    Delete(view)
    del view
    QtCore.QCoreApplication.sendPostedEvents(None, QtCore.QEvent.DeferredDelete)
    view = CreateView("ContextualAORenderView")
    if remote:
        view.RemoteRenderThreshold = 0
    AssignViewToLayout(view=view, layout=layout, hint=0)
    SetActiveView(view)
    QtCore.QCoreApplication.sendPostedEvents(None, QtCore.QEvent.DeferredDelete)
    expect("a new view, before a render", ())
    Show(line, view)
    Render(view)
    expect("a new view with the line", LINE_SETTINGS)
except Exception:  # noqa: BLE001  (reported in the result)
    import traceback
    check(False, "the script ran: %s" % traceback.format_exc())
result.finish()

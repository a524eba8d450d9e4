"""What the GUI startup scripts share (test-gui-script.sh and
test-gui-drag.sh put this folder on PYTHONPATH): the result file's ok/FAIL
lines and its last line, the GUI's Render View replaced by the Contextual
AO view, and carotid.vtk's streamlines."""
import os

from paraview import simple


class Result:
    """CAO_RESULT: one ok/FAIL line per check, then PASSED, FAILED or SKIPPED."""

    def __init__(self):
        self.out = open(os.environ["CAO_RESULT"], "w")
        self.failures = []

    def check(self, ok, what):
        self.out.write(("ok: " if ok else "FAIL: ") + what + "\n")
        if not ok:
            self.failures.append(what)

    def finish(self, skipped=None):
        """Writes the last line and leaves the GUI (the result is written);
        `skipped`: why the script could not run here (test-gui-script.sh
        then exits 125)."""
        if skipped:
            self.out.write("SKIP: %s\nSKIPPED\n" % skipped)
        else:
            self.out.write("PASSED\n" if not self.failures else "FAILED\n")
        self.out.close()
        os._exit(0)


def pyqt5(result, why):
    """PyQt5's QtCore, QtGui and QtWidgets, for reading and using the GUI's
    own widgets; without PyQt5 the script skips, saying `why` it needs it."""
    try:
        from PyQt5 import QtCore, QtGui, QtWidgets
    except ImportError as e:
        result.finish(skipped="PyQt5 is needed %s (%s); install Debian's python3-pyqt5 "
                      "(.ci/setup.sh does)" % (why, e))
    return QtCore, QtGui, QtWidgets


def contextual_ao_view():
    """The GUI's Render View replaced by a Render View (Contextual AO) in its
    place in the layout, made active; returns (view, layout)."""
    old = simple.GetActiveViewOrCreate("RenderView")
    layout = simple.GetLayout(old)
    simple.Delete(old)
    view = simple.CreateView("ContextualAORenderView")
    simple.AssignViewToLayout(view=view, layout=layout, hint=0)
    simple.SetActiveView(view)
    return view, layout


def carotid_streamlines(view, seeds=150):
    """carotid.vtk (CAO_DATA_DIR) and its Stream Tracer from `seeds` seeds
    in a point cloud, shown in `view` as lines 2 pixels wide; returns
    (carotid, tracer, its display)."""
    carotid = simple.OpenDataFile(os.path.join(os.environ["CAO_DATA_DIR"], "carotid.vtk"))
    tracer = simple.StreamTracer(Input=carotid, SeedType="Point Cloud")
    tracer.Vectors = ["POINTS", "vectors"]
    tracer.SeedType.Center = [137.0, 104.0, 23.0]
    tracer.SeedType.Radius = 12.0
    tracer.SeedType.NumberOfPoints = seeds
    tracer.MaximumStreamlineLength = 200.0
    display = simple.Show(tracer, view)
    display.LineWidth = 2.0
    return carotid, tracer, display

"""Streamlines in the Contextual AO view in the ParaView GUI (a startup
script under Xvfb, ParaView's default settings): carotid.vtk's Stream
Tracer drawn as lines over an opaque slice, rendered with Surface AO
Backend CPU and OpenGL (the view's own context): line AO runs in the GUI's
frames (the report's lines section: pixels found and darkened), the
slice gets its AO in the same frame, the slice's 3D widget (drawn in the
view's renderer: its outline and normal are lines) is not taken for lines
(before SceneActors left widgets out, the report counted 2 line actors
here), no error in the report, and (checked
by test-gui-script.sh) no "Error in cache state" from VTK in the GUI's
log. Control: Line AO off leaves no lines section.
Writes CAO_RESULT (ok/FAIL lines, then PASSED or FAILED) and a screenshot
per backend beside it."""
import json
import os

from paraview.simple import *  # noqa: F401,F403

from gui_scene import Result, carotid_streamlines, contextual_ao_view

result = Result()
check = result.check


try:
    LoadPlugin(os.environ["CAO_PLUGIN"], remote=False, ns=globals())
    import contextualao  # noqa: F401  (wraps vtkContextualAOPass)
    view, layout = contextual_ao_view()
    carotid, tracer, lines = carotid_streamlines(view)
    cut = Slice(Input=carotid)
    cut.SliceType.Origin = [137.5, 104.0, 12.0]
    cut.SliceType.Normal = [0.0, 0.0, 1.0]
    Show(cut, view)
    view.CameraPosition = [137.5, 40.0, 70.0]
    view.CameraFocalPoint = [137.5, 104.0, 20.0]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.ResetCamera()
    chain = view.GetRenderer().GetPass()
    while chain is not None and chain.GetClassName() != "vtkContextualAOPass":
        chain = chain.GetDelegatePass() if hasattr(chain, "GetDelegatePass") else None
    check(chain is not None, "the pass is in the view's render pass chain")
    for backend in ("CPU", "OpenGL"):
        view.SurfaceAOBackend = backend
        Render(view)
        SaveScreenshot(os.environ["CAO_RESULT"] + "-%s.png" % backend, view, ImageResolution=[400, 300])
        Render(view)
        report = json.loads(chain.GetLastFrameReport())
        found = report.get("lines", {})
        check(found.get("pixels", 0) > 300 and found.get("combined_pixels", 0) == found.get("pixels") and
              report.get("combined_pixels", 0) > 1000 and "error" not in report and found.get("actors") == 1,
              "Backend %s: %d line pixels darkened, of %d line actor(s) (the streamlines; not the slice "
              "widget's outline), %d surface pixels, no error (%s)"
              % (backend, found.get("combined_pixels", 0), found.get("actors", 0), report.get("combined_pixels", 0),
                 report.get("error", report.get("backend_note", ""))))
    view.LineAOMethod = 0
    Render(view)
    check("lines" not in json.loads(chain.GetLastFrameReport()), "control: Line AO Method None, no line work")
except Exception as e:  # noqa: BLE001  (reported as a failure)
    check(False, "exception: %r" % (e,))
finally:
    result.finish()

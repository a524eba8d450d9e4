"""A Contextual AO Volume's first frame in the ParaView GUI (a startup
script under Xvfb), in the Contextual AO view with an isosurface: the
mapper's LAO precompute fires ProgressEvents inside the render, which the
GUI answers by painting its other OpenGL widgets. The frame must still be
drawn in the view's own context: no mapper error (the ray cast once failed
with GL_INVALID_OPERATION), frames counted, and (checked by
test-gui-script.sh) no "Error in cache state" from VTK in the GUI's log.
Negative control: without the mapper's context restore
(vtkCAO::AroundForeignEvents) this script logged 17 cache-state warnings
and the ray-cast error.
Writes CAO_RESULT (ok/FAIL lines, then PASSED or FAILED)."""
import os

from paraview.simple import *  # noqa: F401,F403

from gui_scene import Result, contextual_ao_view

result = Result()
check = result.check


try:
    LoadPlugin(os.environ["CAO_PLUGIN"], remote=False, ns=globals())
    import contextualao  # noqa: F401  (wraps vtkContextualAOVolumeMapper)
    view, layout = contextual_ao_view()
    reader = OpenDataFile(os.path.join(os.environ["CAO_DATA_DIR"], "HeadMRVolume.mhd"))
    contour = Contour(Input=reader, ContourBy=["POINTS", "MetaImage"], Isosurfaces=[120])
    Show(contour, view)
    display = Show(reader, view)
    display.SetRepresentationType("Contextual AO Volume")
    ColorBy(display, ("POINTS", "MetaImage"))
    GetOpacityTransferFunction("MetaImage").Points = [0, 0, 0.5, 0, 60, 0, 0.5, 0, 255, 0.5, 0.5, 0]
    view.ResetCamera()
    mapper = display.GetClientSideObject().GetActiveRepresentation().GetActor().GetMapper()
    errors = []
    mapper.AddObserver("ErrorEvent", lambda obj, event: errors.append(event))
    for backend in ("CPU", "OpenGL"):
        view.SurfaceAOBackend = backend
        Render(view)
        SaveScreenshot(os.environ["CAO_RESULT"] + "-%s.png" % backend, view, ImageResolution=[400, 300])
    check(mapper.GetFrameCount() >= 2 and not errors,
          "the volume's frames are drawn in the view's context (%d frame(s), %d mapper error(s))"
          % (mapper.GetFrameCount(), len(errors)))
except Exception as e:  # noqa: BLE001  (reported as a failure)
    check(False, "exception: %r" % (e,))
finally:
    result.finish()

"""Two render views showing a "Contextual AO Volume" each, and pvpython
ending normally: no OpenGL error at exit (test-views-at-exit.sh checks the
output after the script ends).

Each view's mapper holds its GL objects in its own window's context. At
exit ParaView deletes the representations while another view's window is
current; the mapper released its objects in that context, and the next VTK
framebuffer check reported "failed at glDeleteFramebuffers 1 OpenGL errors
detected (1281) Invalid value" with 2 or 3 views (never with 1). This
script also checks that both views draw the volume, so that the exit is
the one of views that used the mapper.

  pvpython TestViewsAtExit.py PLUGIN.so DATA_DIR OUT_DIR"""
import os
import sys

from paraview.simple import *  # noqa: F401,F403

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import volume_phantom  # noqa: E402

LoadPlugin(sys.argv[1], remote=False, ns=globals())
out = sys.argv[3]
os.makedirs(out, exist_ok=True)
reader = OpenDataFile(os.path.join(sys.argv[2], "HeadMRVolume.mhd"))
failures = []
for i in range(2):
    view = CreateView("RenderView")
    view.OrientationAxesVisibility = 0
    display = Show(reader, view)
    ColorBy(display, ("POINTS", "MetaImage"))
    display.SetRepresentationType("Contextual AO Volume")
    display.ClipShape = "Sphere" if i else "None"
    ResetCamera(view)
    shot = volume_phantom.picture(view, os.path.join(out, "view-%d.png" % i), 160)
    drawn = volume_phantom.covered(shot)
    print("%s: view %d draws the volume on %.1f%% of its pixels" % ("ok" if drawn > 0.05 else "FAIL", i,
                                                                   100 * drawn))
    if drawn <= 0.05:
        failures.append("view %d drew nothing" % i)
if failures:
    print("FAILED: " + "; ".join(failures))
    sys.exit(1)
print("views drawn; exiting")

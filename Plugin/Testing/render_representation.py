# The plugin's filters and its "Contextual AO Volume" representation on a
# real volume (Data/HeadMRVolume.mhd), rendered to a screenshot. Run by
# test-screenshot.sh in pvpython, in pvbatch, and in the ParaView GUI
# (paraview --script=..., which has no --exit for startup scripts, so the
# GUI run quits with os._exit). CAO_SCREENSHOT names the output PNG; a
# text file beside it says the script finished.
import os

from paraview.simple import *  # noqa: F401,F403

out = os.environ["CAO_SCREENSHOT"]
try:
    LoadPlugin(os.environ["CAO_PLUGIN"], remote=False, ns=globals())
    reader = OpenDataFile(os.path.join(os.environ["CAO_DATA_DIR"], "HeadMRVolume.mhd"))
    # The LAO filter upstream (its AO array travels with the volume).
    lao = LocalAmbientOcclusion(Input=reader)
    lao.RayPattern = "6 rays (faces)"
    lao.Backend = "CPU"
    view = GetActiveViewOrCreate("RenderView")
    view.OrientationAxesVisibility = 0
    view.Background = [1.0, 1.0, 1.0]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    display = Show(lao, view)
    ColorBy(display, ("POINTS", "MetaImage"))
    display.SetRepresentationType("Contextual AO Volume")
    lut = GetColorTransferFunction("MetaImage")
    lut.ApplyPreset("Warm to Cool", True)
    pwf = GetOpacityTransferFunction("MetaImage")
    pwf.Points = [0.0, 0.0, 0.5, 0.0, 40.0, 0.0, 0.5, 0.0, 90.0, 0.4, 0.5, 0.0, 255.0, 0.9, 0.5, 0.0]
    # The upstream LAO occludes with the opacity the view shows; the
    # representation draws its AO (Use Upstream LAO) and continues it under
    # the clip with the same opacity and settings.
    lao.OpacityFunction = pwf
    lao.ScalarOpacityUnitDistance = display.ScalarOpacityUnitDistance
    display.Shade = 1
    display.Ambient = 0.6
    display.Diffuse = 0.5
    display.AORayPattern = "6 rays (faces)"
    display.ClipShape = "Sphere"
    display.ClipScale = [60.0, 60.0, 60.0]
    display.ClipPosition = [94.0, 60.0, 82.0]
    view.CameraPosition = [94.0, -500.0, 82.0]
    view.CameraFocalPoint = [94.0, 122.0, 82.0]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.CameraParallelProjection = 1
    view.CameraParallelScale = 120.0
    Render(view)
    SaveScreenshot(out, view, ImageResolution=[240, 240])
    open(out + ".done", "w").write("ok\n")
finally:
    if os.environ.get("CAO_GUI") == "1":
        os._exit(0)

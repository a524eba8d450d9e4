# Run by the ParaView GUI (paraview --script=...) under Xvfb, from
# test-gui.sh: load the plugin, apply Local Ambient Occlusion to a real
# volume, show the AO on a slice, save a screenshot, and quit.
import os

from paraview.simple import *  # noqa: F401,F403

out = os.environ["CAO_GUI_OUTPUT"]
try:
    LoadPlugin(os.environ["CAO_PLUGIN"], remote=False, ns=globals())
    reader = OpenDataFile(os.path.join(os.environ["CAO_DATA_DIR"], "HeadMRVolume.mhd"))
    lao = LocalAmbientOcclusion(Input=reader)
    lao.RayPattern = "14 rays (faces + corners)"
    lao.Backend = "CPU"
    view = GetActiveViewOrCreate("RenderView")
    view.OrientationAxesVisibility = 0
    display = Show(lao, view)
    display.SetRepresentationType("Slice")
    ColorBy(display, ("POINTS", "AmbientOcclusion"))
    lut = GetColorTransferFunction("AmbientOcclusion")
    lut.ApplyPreset("Grayscale", True)
    lut.RescaleTransferFunction(0.0, 1.0)
    view.CameraPosition = [94.0, 122.0, 700.0]
    view.CameraFocalPoint = [94.0, 122.0, 82.0]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.CameraParallelProjection = 1
    view.CameraParallelScale = 130.0
    Render(view)
    SaveScreenshot(out + ".png", view, ImageResolution=[240, 240])
    open(out + ".txt", "w").write("ok\n")
finally:
    os._exit(0)  # the GUI has no --exit for startup scripts

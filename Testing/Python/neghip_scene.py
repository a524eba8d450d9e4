"""The neghip scene the occluder tests share (TestMapperOccluders.py,
TestPassVolumeOccluders.py; the window also TestPassMultisampled.py and
TestPassVolumeArray.py): an EGL window (or the skip, 125, when there is
none and CAO_REQUIRE_GL is not set), neghip.slc drawn by
vtkContextualAOVolumeMapper with one transfer function and volume
property, and a frame grabbed as an (h, w, 3) int array."""
import os
import sys

from contextualao import vtkContextualAOEGLWindow, vtkContextualAOVolumeMapper
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkRenderingCore import (vtkColorTransferFunction, vtkRenderer, vtkVolume, vtkVolumeProperty,
                                         vtkWindowToImageFilter)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401


def window_and_renderer(size=240, height=None):
    """A size x size (or size x height) EGL window with a white-background
    renderer, or exit (125 when there is no EGL context and CAO_REQUIRE_GL
    is not set)."""
    window = vtkContextualAOEGLWindow()
    if not window.IsUsable():
        if os.environ.get("CAO_REQUIRE_GL", "0") not in ("", "0"):
            sys.exit("no EGL OpenGL 4.3 context (CAO_REQUIRE_GL is set): %s" % window.GetContextError())
        print("skipped: no EGL OpenGL 4.3 context: %s" % window.GetContextError())
        sys.exit(125)
    window.SetSize(size, height if height else size)
    renderer = vtkRenderer()
    renderer.SetBackground(1, 1, 1)
    window.AddRenderer(renderer)
    return window, renderer


def add_volume(renderer, reader):
    """neghip (the reader's output) as a shaded contextual-AO volume; its mapper."""
    opacity = vtkPiecewiseFunction()
    opacity.AddPoint(0, 0.0)
    opacity.AddPoint(40, 0.0)
    opacity.AddPoint(255, 0.8)
    color = vtkColorTransferFunction()
    color.AddRGBPoint(0, 0.9, 0.8, 0.7)
    color.AddRGBPoint(255, 1.0, 0.9, 0.8)
    prop = vtkVolumeProperty()
    prop.SetScalarOpacity(opacity)
    prop.SetColor(color)
    prop.ShadeOn()
    prop.SetAmbient(0.6)
    prop.SetDiffuse(0.5)
    prop.SetInterpolationTypeToLinear()
    mapper = vtkContextualAOVolumeMapper()
    mapper.SetInputConnection(reader.GetOutputPort())
    volume = vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)
    renderer.AddVolume(volume)
    return mapper


def oblique_camera(renderer):
    renderer.ResetCamera()
    renderer.GetActiveCamera().Azimuth(30)
    renderer.GetActiveCamera().Elevation(20)
    renderer.ResetCameraClippingRange()


def frame(window):
    """Render, and the frame's RGB as an (h, w, 3) int array."""
    window.Render()
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.ReadFrontBufferOff()
    grab.ShouldRerenderOff()
    grab.Update()
    image = grab.GetOutput()
    w, h, _ = image.GetDimensions()
    return vtk_to_numpy(image.GetPointData().GetScalars()).reshape(h, w, -1)[:, :, :3].astype(int)

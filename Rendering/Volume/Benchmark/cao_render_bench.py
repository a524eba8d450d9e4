"""Frame times of three volume renderers side by side, in one run, on one
window (vtkContextualAOEGLWindow: EGL, no X), at the same image size and
sample distance:

  1. vtkContextualAOVolumeMapper, contextual AO updated every frame while
     a clip sphere moves (the mapper's report gives the stage times);
  2. vtkContextualAOVolumeMapper with AO off (no clip, no AO work);
  3. VTK's vtkOpenGLGPUVolumeRayCastMapper with Shade on.

    /usr/bin/python3 Rendering/Volume/Benchmark/cao_render_bench.py VOLUME \
        [--size 512] [--frames 6] [--rays 6|14|26|54]

Prints a Markdown table of mean frame times (wall clock around
Render + glFinish) and the ratios to VTK's shaded ray caster.
"""
import argparse
import json
import math
import time

from vtkmodules.vtkIOImage import vtkSLCReader, vtkMetaImageReader
from vtkmodules.vtkIOXML import vtkXMLImageDataReader
from vtkmodules.vtkRenderingCore import (vtkActor, vtkColorTransferFunction, vtkPolyDataMapper,
                                         vtkRenderer, vtkVolume, vtkVolumeProperty)
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkRenderingVolumeOpenGL2 import vtkOpenGLGPUVolumeRayCastMapper
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
import contextualao as cao

RAYS = {"6": 0, "14": 1, "26": 2, "54": 3}


def read(path):
    r = vtkSLCReader() if path.endswith(".slc") else (
        vtkMetaImageReader() if path.endswith((".mhd", ".mha")) else vtkXMLImageDataReader())
    r.SetFileName(path)
    r.Update()
    return r.GetOutput()


def main():
    p = argparse.ArgumentParser()
    p.add_argument("volume")
    p.add_argument("--size", type=int, default=512)
    p.add_argument("--frames", type=int, default=6)
    p.add_argument("--rays", default="6", choices=sorted(RAYS))
    a = p.parse_args()
    image = read(a.volume)
    lo, hi = image.GetPointData().GetScalars().GetRange()
    spacing = min(image.GetSpacing())
    step = 0.5 * spacing
    b = image.GetBounds()
    centre = [(b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2]
    extent = min(b[1] - b[0], b[3] - b[2], b[5] - b[4])

    win = cao.vtkContextualAOEGLWindow()
    if not win.IsUsable():
        raise SystemExit("no EGL context: " + win.GetContextError())
    win.SetSize(a.size, a.size)
    ren = vtkRenderer()
    ren.SetBackground(1, 1, 1)
    win.AddRenderer(ren)
    otf = vtkPiecewiseFunction()
    w = hi - lo
    for x, y in ((lo, 0), (lo + 0.18 * w, 0), (lo + 0.35 * w, 0.35), (hi, 0.85)):
        otf.AddPoint(x, y)
    ctf = vtkColorTransferFunction()
    for x, c in ((lo, (0.85, 0.45, 0.25)), (lo + 0.5 * w, (0.95, 0.8, 0.55)), (hi, (1, 1, 0.95))):
        ctf.AddRGBPoint(x, *c)
    prop = vtkVolumeProperty()
    prop.SetScalarOpacity(otf)
    prop.SetColor(ctf)
    prop.SetInterpolationTypeToLinear()
    prop.ShadeOn()
    prop.SetAmbient(0.6)
    prop.SetDiffuse(0.5)
    prop.SetSpecular(0.2)
    vol = vtkVolume()
    vol.SetProperty(prop)
    ren.AddVolume(vol)

    sphere = vtkSphereSource()
    sphere.SetRadius(0.2 * extent)
    sphere.SetThetaResolution(48)
    sphere.SetPhiResolution(24)
    sm = vtkPolyDataMapper()
    sm.SetInputConnection(sphere.GetOutputPort())
    clip = vtkActor()
    clip.SetMapper(sm)

    def pose(i):  # a path through the volume's centre
        t = (i + 0.5) / a.frames - 0.5
        clip.SetPosition(centre[0] + 0.4 * extent * t, centre[1] + 0.2 * extent * t,
                         centre[2] + 0.1 * extent * math.sin(6 * t))

    def timed(label, setup, frames, report=None):
        setup()
        ren.ResetCamera()
        cam = ren.GetActiveCamera()
        cam.Azimuth(30)
        cam.Elevation(20)
        cam.Zoom(1.3)
        ren.ResetCameraClippingRange()
        t0 = time.perf_counter()
        win.Render()  # warm-up: uploads, precompute
        warm = time.perf_counter() - t0
        times, stages = [], []
        for i in range(frames):
            pose(i)
            cam.Azimuth(2)  # the camera moves too: every frame is redrawn
            t0 = time.perf_counter()
            win.Render()
            times.append(1000 * (time.perf_counter() - t0))
            if report:
                stages.append(json.loads(report()))
        return label, warm * 1000, times, stages

    caom = cao.vtkContextualAOVolumeMapper()
    caom.SetInputData(image)
    caom.SetQualityToCustom()  # --rays applies
    caom.SetRayPattern(RAYS[a.rays])
    caom.SetSampleDistance(step)
    caom.SetClipShape(clip)
    rows = [timed("ours, CAO updated every frame (clip sphere moving, %s rays)" % a.rays,
                  lambda: vol.SetMapper(caom), a.frames, caom.GetLastFrameReport)]
    plain = cao.vtkContextualAOVolumeMapper()
    plain.SetInputData(image)
    plain.SetSampleDistance(step)
    plain.AmbientOcclusionOff()
    rows.append(timed("ours, AO off", lambda: vol.SetMapper(plain), a.frames))
    vtkm = vtkOpenGLGPUVolumeRayCastMapper()
    vtkm.SetInputData(image)
    vtkm.AutoAdjustSampleDistancesOff()
    vtkm.SetSampleDistance(step)
    rows.append(timed("VTK vtkOpenGLGPUVolumeRayCastMapper, Shade on", lambda: vol.SetMapper(vtkm),
                      a.frames))

    dims = image.GetDimensions()
    print("volume %s (%dx%dx%d), %dx%d pixels, sample distance %g, %d frames each, %s"
          % (a.volume, dims[0], dims[1], dims[2], a.size, a.size, step, a.frames,
             win.GetContextDescription()))
    ref = sum(rows[2][2]) / len(rows[2][2])
    print("| renderer | first frame ms | mean frame ms | ratio to VTK shaded |")
    print("|---|---:|---:|---:|")
    for label, warm, times, _ in rows:
        mean = sum(times) / len(times)
        print("| %s | %.0f | %.1f | %.2fx |" % (label, warm, mean, mean / ref))
    stages = rows[0][3]
    if stages:
        names = ["classify", "copy", "recompute", "ao_samples", "raycast"]
        mean = {n: sum(s2["ms"] for f in stages for s2 in f["stages"] if s2["name"] == n)
                / len(stages) for n in names}
        vox = sum(f["recomputed_voxels"] for f in stages) / len(stages)
        print("\nCAO frames, mean per stage (ms, %s): %s; voxels recomputed per frame: %.0f (%.2f%%)"
              % (stages[0]["stages"][0]["timer"],
                 ", ".join("%s %.1f" % (n, mean[n]) for n in names), vox,
                 100.0 * vox / (dims[0] * dims[1] * dims[2])))


if __name__ == "__main__":
    main()

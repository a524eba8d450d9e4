# The plugin's filters in a ParaView process that renders, with every
# Backend (Auto, CPU, OpenGL), in pvpython, pvbatch and the GUI (run by
# test-host-context.sh, which also fails on any "ERR|" or "Error in cache
# state" line in the process's log). Two orders (CAO_ORDER):
#  - view-first: the order the GUI uses. A render view exists and has
#    rendered (its GLX context is current on this thread) before the LAO
#    filter runs, then the filter's output is shown with the "Contextual AO
#    Volume" representation and saved; a headless context made current over
#    the view's used to leave it stale ("Error in cache state for GL_...",
#    then SIGABRT).
#  - filters-first: LAO, depth maps and CAO run before any view exists (a
#    headless context left current would make the view's GLX context fail
#    to become current), then a view shows the result, then the filters run
#    again with the view's context current.
# Each backend's label is checked (Auto never brings in a second context
# while the view's is current), the OpenGL AO is within 1e-5 of the CPU's,
# and each screenshot shows the volume (not just the background).
# Writes CAO_OUT/<order>-<backend>.png and CAO_OUT/done.txt when it finished.
import os
import sys

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm

out_dir = os.environ["CAO_OUT"]
order = os.environ.get("CAO_ORDER", "view-first")
gui = os.environ.get("CAO_GUI") == "1"
failures = []


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what, flush=True)
    if not ok:
        failures.append(what)


def label(proxy):
    data = sm.Fetch(proxy)
    arr = data.GetFieldData().GetAbstractArray("ComputeBackend")
    return arr.GetValue(0) if arr else "?"


def ao_values(proxy):
    data = sm.Fetch(proxy)
    arr = data.GetPointData().GetArray("AmbientOcclusion")
    return [arr.GetValue(i) for i in range(arr.GetNumberOfTuples())]


def shows_volume(path):
    """Whether at least 5% of the pixels differ from the corner (background)."""
    from vtkmodules.vtkIOImage import vtkPNGReader
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    img = reader.GetOutput()
    scalars = img.GetPointData().GetScalars()
    n = scalars.GetNumberOfTuples()
    comps = min(3, scalars.GetNumberOfComponents())
    bg = [scalars.GetComponent(0, c) for c in range(comps)]
    differ = sum(1 for i in range(n)
                 if max(abs(scalars.GetComponent(i, c) - bg[c]) for c in range(comps)) > 10)
    return differ / float(n) >= 0.05, differ / float(n)


def expect_label(backend, text, view_current):
    if backend == "CPU":
        check(text == "CPU", f"{backend}: ran on {text}")
    elif backend == "OpenGL":
        check(text.startswith("OpenGL (egl") or text.startswith("OpenGL (osmesa"),
              f"{backend}: ran on a headless context: {text}")
    else:
        # llvmpipe here: Auto takes the CPU, with the reason; with the view's
        # context current on this thread, never a second context.
        check(text.startswith("CPU (Auto"), f"{backend}: ran on the CPU by choice: {text}")
        if view_current:
            check("renders with an application's" in text or "software rasteriser" in text,
                  f"{backend}: says why: {text}")


def filters(reader, backend):
    lao = LocalAmbientOcclusion(Input=reader)
    lao.Backend = backend
    lao.Reach = 32.0  # 8 voxels, what the maps are dilated for
    sphere = Sphere(Radius=40, ThetaResolution=32, PhiResolution=16)
    maps = ClipDepthMaps(Input=sphere, Reach=32.0, VoxelSpacing=[4, 4, 4])
    maps.Backend = backend
    cao = ContextualAmbientOcclusion(Input=lao, DepthMaps=maps)
    cao.Backend = backend
    cao.PoseTransform.Translate = [94, 120, 82]
    cao.UpdatePipeline()
    return lao, sphere, maps, cao


def screenshot(view, source, name):
    display = Show(source, view)
    ColorBy(display, ("POINTS", "MetaImage"))
    display.SetRepresentationType("Contextual AO Volume")
    ResetCamera(view)
    path = os.path.join(out_dir, name + ".png")
    SaveScreenshot(path, view, ImageResolution=[200, 200])
    ok, fraction = shows_volume(path)
    check(ok, f"{name}: the screenshot shows the volume ({100 * fraction:.1f}% of pixels)")
    Hide(source, view)


try:
    if "CAO_PLUGIN" in os.environ:
        LoadPlugin(os.environ["CAO_PLUGIN"], remote=False, ns=globals())
    reader = OpenDataFile(os.path.join(os.environ["CAO_DATA_DIR"], "HeadMRVolume.mhd"))
    ao = {}
    if order == "view-first":
        view = GetActiveViewOrCreate("RenderView") if gui else CreateView("RenderView")
        Render(view)
        for backend in ("Auto", "CPU", "OpenGL"):
            # The script: the LAO filter with this backend, shown in
            # a view that rendered before it ran.
            lao = LocalAmbientOcclusion(Input=reader)
            lao.Backend = backend
            screenshot(view, lao, f"{order}-{backend}")
            expect_label(backend, label(lao), view_current=not gui)
            ao[backend] = ao_values(lao)
            # The other two filters, with the view's context current.
            parts = filters(reader, backend)
            expect_label(backend, label(parts[3]), view_current=not gui)
            Render(view)
    else:
        results = {}
        for backend in ("Auto", "CPU", "OpenGL"):
            parts = filters(reader, backend)
            results[backend] = parts
            expect_label(backend, label(parts[0]), view_current=False)
            ao[backend] = ao_values(parts[0])
        view = CreateView("RenderView")
        Render(view)
        for backend in ("Auto", "CPU", "OpenGL"):
            screenshot(view, results[backend][3], f"{order}-{backend}")
            lao = results[backend][0]
            lao.Quality = "Custom"
            lao.RayPattern = "14 rays (faces + corners)"  # runs again, view current
            results[backend][3].UpdatePipeline()
            expect_label(backend, label(results[backend][3]), view_current=True)
            Render(view)
    diff = max(abs(a - b) for a, b in zip(ao["OpenGL"], ao["CPU"]))
    check(diff <= 1e-5, f"OpenGL vs CPU AO: max |diff| {diff:.3g} (<= 1e-5, the 16-bit storage)")
    d2 = max(abs(a - b) for a, b in zip(ao["Auto"], ao["CPU"]))
    sizes = (len(ao["Auto"]), len(ao["CPU"]))
    check(d2 == 0.0 and sizes[0] == sizes[1],
          f"Auto (on the CPU here) equals CPU (max |diff| {d2:.3g}, sizes {sizes})")
    with open(os.path.join(out_dir, "done.txt"), "w") as f:
        f.write("FAIL\n" if failures else "ok\n")
        f.write("\n".join(failures) + "\n")
finally:
    sys.stdout.flush()
    if gui:
        os._exit(0)

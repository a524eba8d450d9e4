"""Progress and abort of a long LAO run, the way ParaView's progress bar and
its abort button drive a filter: ProgressEvents at a steady granularity,
and SetAbortExecuteAndUpdateTime() from an observer stops the run promptly
(within one progress block) and leaves an empty output flagged ABORTED by
the executive, never a partial AO. The next update runs to completion.
Both backends: the CPU, and OpenGL (skipped without an OpenGL 4.3 context).

The volume mapper's own LAO precompute (what the ParaView representation
runs when it computes its own AO) reports progress the same way, and an
abort from a progress observer stops it within one slab; the frame draws
nothing and the next frame precomputes again, to completion.
"""
import os
import sys

import contextualao as cao
from vtkmodules.vtkCommonExecutionModel import vtkAlgorithm
from vtkmodules.vtkIOImage import vtkSLCReader

data = os.environ["CAO_DATA_DIR"]
failures = []


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


reader = vtkSLCReader()
reader.SetFileName(os.path.join(data, "neghip.slc"))
reader.Update()


def long_run(backend, rays, abort_at):
    """Returns the progress values seen and the filter, aborted at `abort_at`."""
    lao = cao.vtkLocalAmbientOcclusion()
    lao.SetInputConnection(reader.GetOutputPort())
    lao.SetQualityToCustom()  # the settings below apply
    lao.SetSampleDensity(1.0)
    lao.SetRayPattern(lao.FIBONACCI)
    lao.SetNumberOfRays(rays)
    lao.SetReach(24.0)  # 24 samples per ray: about 7 s for 1024 rays on 2 cores, unaborted
    lao.SetBackend(backend)
    seen = []

    def on_progress(obj, event):
        seen.append(obj.GetProgress())
        if abort_at is not None and obj.GetProgress() >= abort_at and not obj.GetAbortExecute():
            obj.SetAbortExecuteAndUpdateTime()

    lao.AddObserver("ProgressEvent", on_progress)
    lao.Update()
    return seen, lao


for backend, name, rays in ((cao.vtkLocalAmbientOcclusion.CPU, "CPU", 1024),
                            (cao.vtkLocalAmbientOcclusion.OPENGL, "OpenGL", 256)):
    if backend == cao.vtkLocalAmbientOcclusion.OPENGL:
        probe = cao.vtkLocalAmbientOcclusion()
        probe.SetInputConnection(reader.GetOutputPort())
        probe.SetBackend(backend)
        probe.SetRayPattern(probe.RAYS_6)
        probe.Update()
        if probe.GetOutput().GetPointData().GetArray("AmbientOcclusion") is None:
            # Where OpenGL is required (CAO_REQUIRE_GL, set by .ci/run), a
            # backend that cannot run is a failure, not a skip.
            check(os.environ.get("CAO_REQUIRE_GL", "0") in ("", "0"),
                  "the OpenGL backend ran (CAO_REQUIRE_GL is set)")
            print("skip the OpenGL backend: no OpenGL 4.3 context")
            continue
    seen, lao = long_run(backend, rays, 0.2)
    before_abort = [p for p in seen if p < 0.2]
    after_abort = [p for p in seen if 0.2 <= p < 1.0]
    check(len(before_abort) >= 10, "%s: at least 10 progress events before 20%% (%d)"
          % (name, len(before_abort)))
    check(all(b >= a for a, b in zip(seen, seen[1:-1])), "%s: progress never goes back" % name)
    steps = [b - a for a, b in zip(seen, seen[1:]) if b < 1.0]
    check(max(steps) <= 0.06, "%s: no progress step above 6%% (largest %.3f)" % (name, max(steps)))
    # Promptly: the run stops at the first check after the request, i.e.
    # within one progress block (at most 5% of the work) past 20%.
    check(len(after_abort) == 1 and after_abort[0] < 0.26,
          "%s: stopped within one block of the abort (progress after it: %s)"
          % (name, ["%.3f" % p for p in after_abort]))
    info = lao.GetOutputInformation(0)
    check(info.Has(vtkAlgorithm.ABORTED()) and info.Get(vtkAlgorithm.ABORTED()) == 1,
          "%s: the output is flagged ABORTED" % name)
    out = lao.GetOutput()
    check(out.GetPointData().GetArray("AmbientOcclusion") is None and out.GetNumberOfPoints() == 0,
          "%s: the aborted output is empty, not a partial AO" % name)
    # The next update (abort flag cleared, as ParaView does) completes.
    lao.RemoveAllObservers()
    lao.SetAbortExecute(0)
    lao.SetNumberOfRays(16)
    lao.Update()
    ao = lao.GetOutput().GetPointData().GetArray("AmbientOcclusion")
    check(ao is not None and ao.GetNumberOfTuples() == 66 ** 3 and not info.Get(vtkAlgorithm.ABORTED()),
          "%s: the next update completes and is not flagged" % name)


# The mapper's precompute, in an EGL window (no X).
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction  # noqa: E402
from vtkmodules.vtkRenderingCore import vtkRenderer, vtkVolume, vtkVolumeProperty  # noqa: E402
from vtkmodules.vtkCommonCore import vtkCommand  # noqa: E402
window = cao.vtkContextualAOEGLWindow()
if not window.IsUsable():
    check(os.environ.get("CAO_REQUIRE_GL", "0") in ("", "0"),
          "an EGL window for the mapper (CAO_REQUIRE_GL is set): %s" % window.GetContextError())
    print("skip the mapper: no EGL OpenGL 4.3 context")
else:
    mapper = cao.vtkContextualAOVolumeMapper()
    mapper.SetInputConnection(reader.GetOutputPort())
    mapper.SetQualityToCustom()  # the settings below apply
    mapper.SetSampleDensity(1.0)
    mapper.SetRayPattern(mapper.FIBONACCI)
    mapper.SetNumberOfRays(48)
    mapper.SetReach(16.0)
    opacity = vtkPiecewiseFunction()
    opacity.AddPoint(40, 0.0)
    opacity.AddPoint(255, 0.8)
    prop = vtkVolumeProperty()
    prop.SetScalarOpacity(opacity)
    volume = vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)
    window.SetSize(64, 64)
    renderer = vtkRenderer()
    window.AddRenderer(renderer)
    renderer.AddVolume(volume)
    renderer.ResetCamera()
    seen = []
    errors = []

    def on_mapper_progress(obj, event):
        seen.append(obj.GetProgress())
        if obj.GetProgress() >= 0.2 and not obj.GetAbortExecute():
            obj.SetAbortExecute(1)

    tag = mapper.AddObserver("ProgressEvent", on_mapper_progress)
    err = mapper.AddObserver(vtkCommand.ErrorEvent, lambda o, e: errors.append(e))
    frames = mapper.GetFrameCount()
    window.Render()
    after = [p for p in seen if 0.2 <= p < 1.0]
    check(len([p for p in seen if p < 0.2]) >= 5 and len(after) == 1 and after[0] < 0.26 and
          all(b >= a for a, b in zip(seen, seen[1:])),
          "mapper: progress in steps, never back, stopped within one slab of the abort (%s)"
          % ["%.3f" % p for p in seen])
    check(mapper.GetFrameCount() == frames and mapper.GetPrecomputeCount() == 0 and not errors,
          "mapper: the aborted frame is not drawn, no precompute counted, no error (%d frames, "
          "%d precomputes, errors %s)" % (mapper.GetFrameCount() - frames,
                                         mapper.GetPrecomputeCount(), errors))
    mapper.RemoveObserver(tag)
    seen = []
    mapper.AddObserver("ProgressEvent", lambda o, e: seen.append(o.GetProgress()))
    window.Render()
    check("precompute" in mapper.GetLastFrameStages() and seen and seen[-1] == 1.0 and
          mapper.GetFrameCount() == frames + 1 and mapper.GetPrecomputeCount() == 1 and not errors,
          "mapper: the next frame precomputes to completion (%s; last progress %s)"
          % (mapper.GetLastFrameStages(), seen[-1] if seen else None))

print("%d failure(s)" % len(failures))
sys.exit(1 if failures else 0)

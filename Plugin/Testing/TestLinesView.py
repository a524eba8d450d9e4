"""Lines in the "Render View (Contextual AO)" view, in pvpython or pvbatch:
streamlines of carotid.vtk (ParaView's Stream Tracer, drawn as lines) beside
an opaque slice of the same field, as a user builds the scene:
- the lines get line AO in the same frame as the slice gets its surface AO
  (the report's "lines" and the surfaces' combined pixels);
- against Line AO off (the control) the picture only darkens (the lines,
  and the slice where the lines occlude it), FXAA off for the comparison;
- a colour change runs only the combine; Line AO Samples reaches the pass;
- after a dolly into the lines (a near plane close to the camera) their
  pixels are still found;
- Render Lines As Tubes: the lines' pixels are still found and darkened
  (more of them: the tubes are wider);
- a camera drag step (an interactive render) keeps the lines' grid, the
  still render at the release builds the camera's own; the drag's AO near
  the exact one;
- Surface AO Method None leaves the lines their line AO, with no surface
  step; with Line AO Method None too no stage runs.
Writes OUT_DIR/lines-off.png and lines-on.png (and without FXAA).

  pvpython TestLinesView.py PLUGIN.so DATA_DIR OUT_DIR   (under run-with-xvfb.sh)"""
import json
import os
import sys

from paraview.simple import *  # noqa: F401,F403
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.util.numpy_support import vtk_to_numpy

LoadPlugin(sys.argv[1], remote=False, ns=globals())
import contextualao  # noqa: E402,F401  (wraps vtkContextualAOPass)
data, out = sys.argv[2], sys.argv[3]
os.makedirs(out, exist_ok=True)
failures = []
W, H = 400, 300


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


def shot(name):
    path = os.path.join(out, name + ".png")
    SaveScreenshot(path, view, ImageResolution=[W, H])
    r = vtkPNGReader()
    r.SetFileName(path)
    r.Update()
    return vtk_to_numpy(r.GetOutput().GetPointData().GetScalars()).astype(float)[:, :3].reshape(H, W, 3)


def field(report, key):
    """The number after "key": in the report's lines section (-1: none)."""
    at = report.find('"lines": {')
    if at < 0:
        return -1.0
    section = report[at:report.find("}", at)]
    k = section.find('"%s": ' % key)
    return float(section[k + len(key) + 4:].split(",")[0].split("}")[0]) if k >= 0 else -1.0


view = CreateView("ContextualAORenderView")
view.OrientationAxesVisibility = 0
view.ViewSize = [W, H]
carotid = LegacyVTKReader(FileNames=[os.path.join(data, "carotid.vtk")])
tracer = StreamTracer(Input=carotid, SeedType="Point Cloud")
tracer.Vectors = ["POINTS", "vectors"]
tracer.SeedType.Center = [137.0, 104.0, 23.0]
tracer.SeedType.Radius = 12.0
tracer.SeedType.NumberOfPoints = 300
tracer.MaximumStreamlineLength = 200.0
lines = Show(tracer, view)
ColorBy(lines, None)
lines.AmbientColor = lines.DiffuseColor = [0.95, 0.85, 0.6]
lines.LineWidth = 2.0
cut = Slice(Input=carotid)
cut.SliceType.Origin = [137.5, 104.0, 12.0]
cut.SliceType.Normal = [0.0, 0.0, 1.0]
plane = Show(cut, view)
ColorBy(plane, None)
view.CameraPosition = [137.5, 40.0, 70.0]
view.CameraFocalPoint = [137.5, 104.0, 20.0]
view.CameraViewUp = [0.0, 0.0, 1.0]
ResetCamera(view)
chain = view.GetRenderer().GetPass()
while chain is not None and chain.GetClassName() != "vtkContextualAOPass":
    chain = chain.GetDelegatePass() if hasattr(chain, "GetDelegatePass") else None
check(chain is not None, "the pass is in the view's render pass chain")
pas = chain
Render(view)
print("first frame: " + pas.GetLastFrameReport())
on = shot("lines-on")
report = pas.GetLastFrameReport()
print("report: " + report)
segments, combined = field(report, "segments"), field(report, "combined_pixels")
surfaceCombined = float(report.split('"combined_pixels": ')[1].split(",")[0])
check(segments > 1000 and combined > 300 and field(report, "voxelizations") >= 1,
      "the streamlines get line AO: %d segments, %d line pixels darkened" % (segments, combined))
check(surfaceCombined > 1000, "the slice gets its surface AO in the same frame (%d pixels)" % surfaceCombined)
# Without FXAA (the Render View's default): it re-blends the pixels beside
# the darkened lines, a background pixel by up to 10 grey levels brighter;
# the comparison asks the AO itself never to brighten.
view.UseFXAA = 0
on = shot("lines-on-no-fxaa")
view.LineAOMethod = 0
off = shot("lines-off-no-fxaa")
view.UseFXAA = 1
shot("lines-off")
check(field(pas.GetLastFrameReport(), "segments") == -1.0, "Line AO off: no line work")
darker = (off - on).mean(axis=2)
changed = int((darker > 10).sum())
# FXAA (the Render View's default) re-blends edge pixels next to darkened
# ones: a few grey levels brighter at most; the AO itself never brightens.
worst = divmod(int(darker.argmin()), W)
print("largest brightening %.1f at row %d, column %d: on %s, off %s" % (-darker.min(), worst[0], worst[1],
      on[worst].tolist(), off[worst].tolist()))
check(darker.min() >= 0 and changed > 200,
      "line AO only darkens (largest brightening %.1f): %d pixels darker by more than 10 grey levels"
      % (-darker.min(), changed))
view.LineAOMethod = 1
view.LineAOSamples = 16
Render(view)
check(pas.GetLineSamples() == 16 and "line_ao" in pas.GetLastFrameStages(),
      "Line AO Samples reaches the pass and re-estimates (%s)" % pas.GetLastFrameStages())
lines.AmbientColor = lines.DiffuseColor = [0.6, 0.9, 0.95]
Render(view)
check(pas.GetLastFrameStages() == "combine", "a colour change runs only the combine (%s)" % pas.GetLastFrameStages())
# A dolly into the streamlines: ParaView's near plane comes close (the
# camera inside the data), where its offset of the lines' depth toward the
# camera is many pixels in the world; the lines' pixels are still found.
before = field(pas.GetLastFrameReport(), "pixels")
camera = view.GetActiveCamera()
camera.Dolly(8.0)
Render(view)
near = camera.GetClippingRange()[0]
closeUp = field(pas.GetLastFrameReport(), "pixels")
check(closeUp > before and field(pas.GetLastFrameReport(), "combined_pixels") == closeUp,
      "after a dolly into the lines (near plane %.3f) %d line pixels are found (%d before)" % (near, closeUp, before))
camera.Dolly(1.0 / 8.0)
Render(view)
lines.RenderLinesAsTubes = 1
lines.LineWidth = 5.0
Render(view)
tubes = pas.GetLastFrameReport()
check(field(tubes, "pixels") > 1.1 * field(report, "pixels") and field(tubes, "combined_pixels") > 300,
      "Render Lines As Tubes: %d line pixels (as lines: %d), %d darkened"
      % (field(tubes, "pixels"), field(report, "pixels"), field(tubes, "combined_pixels")))
# A camera drag (ParaView's interactive renders): a drag step keeps the
# lines' grid of the last frame (no voxelize_lines; the report says
# grid_kept) and still gives the lines their AO; the still render at the
# release builds the camera's own grid (the control: a still render after
# the same turn voxelizes). These streamlines are over the view's LOD
# threshold (20 MB): ParaView draws a decimated copy while dragging, a new
# geometry, so its first step builds the lines again and the next ones keep
# that grid; with the threshold raised (no LOD) the first step keeps it.
lines.RenderLinesAsTubes = 0
lines.LineWidth = 2.0


def line_ao():
    return [pas.GetPixelAO(x, y) for y in range(0, H, 2) for x in range(0, W, 2)]


for lod in ("LOD (the default threshold)", "no LOD"):
    view.LODThreshold = 20.0 if lod.startswith("LOD") else 1.0e6
    Render(view)
    steps = []
    for step in range(3):
        camera.Azimuth(4.0)
        view.SMProxy.InteractiveRender()
        steps.append((pas.GetLastFrameStages(), pas.GetLastFrameReport()))
    dragAO = line_ao()
    Render(view)
    stillStages, stillReport = pas.GetLastFrameStages(), pas.GetLastFrameReport()
    stillAO = line_ao()
    both = [(a, b) for a, b in zip(dragAO, stillAO) if a > -1 and b > -1]
    meanGap = sum(abs(a - b) for a, b in both) / max(1, len(both))
    print("%s: drag steps %s; still: %s; %d line pixels, mean |AO(drag) - AO(still)| %.4f"
          % (lod, [st for st, _ in steps], stillStages, len(both), meanGap))
    kept = steps[1:] if lod.startswith("LOD") else steps
    check(all("voxelize_lines" not in st and "line_ao" in st and '"grid_kept"' in rep for st, rep in kept),
          "%s: the drag steps keep the lines' grid and still estimate their AO (%s)" % (lod, [st for st, _ in kept]))
    check("voxelize_lines" in stillStages and '"grid_kept"' not in stillReport,
          "%s: the still render at the release voxelizes the camera's own grid (%s)" % (lod, stillStages))
    if not lod.startswith("LOD"):
        # (The kept grid's prisms run along the drag's start view axis: an
        # approximation, 12 degrees of turn here; bound 0.05.)
        check(len(both) > 300 and meanGap < 0.05,
              "no LOD: the last drag step's line AO is near the still one (mean |difference| %.4f over %d "
              "pixels; bound 0.05)" % (meanGap, len(both)))
view.SurfaceAOMethod = "None"
Render(view)
noneReport = json.loads(pas.GetLastFrameReport())
check(noneReport["method"] == "none" and noneReport.get("lines", {}).get("method") == "lineao" and
      "trace" not in pas.GetLastFrameStages() and "primary" not in pas.GetLastFrameStages(),
      "Surface AO Method None leaves the lines their Line AO Method, no surface step (%s)" % pas.GetLastFrameStages())
view.LineAOMethod = "None"
Render(view)
check(pas.GetLastFrameStages() == "", "Surface and Line AO Method None run nothing")
if failures:
    print("%d failure(s)" % len(failures))
    sys.exit(1)
print("all checks passed")

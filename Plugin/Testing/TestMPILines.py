"""Line AO across MPI processes, in ParaView's view:

    mpirun -np 1 pvbatch TestMPILines.py PLUGIN.so OUTPUT_DIR 1
    mpirun -np 2 pvbatch TestMPILines.py PLUGIN.so OUTPUT_DIR 2

A bundle of 36 wavy polylines, line i on process i mod N (a programmable
source that honours the piece asked for), drawn as tubes, with a sphere
through the bundle split over the processes too; distributed rendering (each
process draws its own, the images composited by depth). Each run saves the
view with the AO off, the lines alone with line AO, and the lines with the
sphere (meshes occlude lines, lines occlude the sphere, on the world grid).
The run on N ranks compares itself with the run on 1: the lines' grid and
solids hold every process's lines and meshes, so the pictures must be the
serial ones; so must the prisms on the window's OpenGL, and a single line
that lies on rank 0 alone beside the split sphere (the other process, with
no lines, still takes part). Negative control: each process's own lines
alone in its grid (the gather replaced by this process's segments, by hand)
gave 0.47 of the serial darkening and 37% of pixels more than 8 levels
apart; before this exchange the lines got no AO in parallel at all."""
import json
import os
import sys

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

plugin, outdir = sys.argv[1], sys.argv[2]
LoadPlugin(plugin, remote=False, ns=globals())
import contextualao  # noqa: F401,E402  (the pass's Python wrapping, for its report)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mpi_view_checks import apart, check, find_pass, finish, ranks_as_started, read  # noqa: E402

ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
ranks_as_started(ranks)

view = CreateView("ContextualAORenderView")
view.OrientationAxesVisibility = 0
view.ViewSize = [320, 240]
view.RemoteRenderThreshold = 0  # distributed rendering, every rank draws its pieces
bundle = ProgrammableSource(OutputDataSetType="vtkPolyData")
bundle.Script = (
    "import math\n"
    "from vtkmodules.vtkCommonCore import vtkPoints\n"
    "from vtkmodules.vtkCommonDataModel import vtkCellArray\n"
    "from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline as sddp\n"
    "info = self.GetOutputInformation(0)\n"
    "piece = info.Get(sddp.UPDATE_PIECE_NUMBER()) if info.Has(sddp.UPDATE_PIECE_NUMBER()) else 0\n"
    "pieces = info.Get(sddp.UPDATE_NUMBER_OF_PIECES()) if info.Has(sddp.UPDATE_NUMBER_OF_PIECES()) else 1\n"
    "points, cells = vtkPoints(), vtkCellArray()\n"
    "for i in range(36):\n"
    "    if i % pieces != piece:\n"
    "        continue\n"
    "    y, z = 0.22 * (i % 6) - 0.55, 0.22 * (i // 6) - 0.55\n"
    "    cells.InsertNextCell(61)\n"
    "    for k in range(61):\n"
    "        x = -1.5 + 3.0 * k / 60.0\n"
    "        cells.InsertCellPoint(points.InsertNextPoint(x, y + 0.05 * math.sin(3 * x + i), z))\n"
    "out = self.GetOutput()\n"
    "out.SetPoints(points)\n"
    "out.SetLines(cells)\n")
lines = Show(bundle, view)
lines.DiffuseColor = [1.0, 1.0, 1.0]
lines.LineWidth = 5.0
lines.RenderLinesAsTubes = 1
ball = Sphere(Center=[0.3, 0.0, 0.0], Radius=0.45, ThetaResolution=48, PhiResolution=24)
view.CameraPosition = [1.2, -3.6, 2.4]
view.CameraFocalPoint = [0.0, 0.0, 0.0]
view.CameraViewUp = [0.0, 0.0, 1.0]
view.SurfaceAOBackend = "CPU"
view.SurfaceAORadius = 0.5
view.LineAOMethod = 1
pas = find_pass(view)
check(pas is not None, "the pass is in the view's render pass chain")


def grey(name):
    path = os.path.join(outdir, "np%d-%s.png" % (ranks, name))
    SaveScreenshot(path, view, ImageResolution=[320, 240])
    return path


reports = {}


def off_and_on(name):
    """The view without AO (NAME-off) and with voxel cones and line AO (NAME)."""
    view.SurfaceAOMethod = "None"
    view.LineAOMethod = "None"
    grey(name + "-off")
    view.SurfaceAOMethod = "Voxel Cones"
    view.LineAOMethod = "Voxelized Lines"
    grey(name)
    reports[name] = json.loads(pas.GetLastFrameReport())


off_and_on("lines")
ballDisplay = Show(ball, view)
ballDisplay.DiffuseColor = [1.0, 1.0, 1.0]
off_and_on("both")
# The prisms on the window's OpenGL, in the same shared grid.
Hide(ball, view)
view.SurfaceAOBackend = "OpenGL"
grey("lines-gl")
reports["lines-gl"] = json.loads(pas.GetLastFrameReport())
view.SurfaceAOBackend = "CPU"
# One line that is not split (a Line source lies on rank 0 only), beside the
# split sphere: a process without lines still takes part (its meshes
# occlude rank 0's line; a process that skipped the collective calls would
# leave the others waiting).
Hide(bundle, view)
Show(ball, view)
single = Line(Point1=[-1.2, -0.3, -0.4], Point2=[1.2, -0.3, -0.4], Resolution=40)
singleDisplay = Show(single, view)
singleDisplay.LineWidth = 6.0
singleDisplay.RenderLinesAsTubes = 1
singleDisplay.DiffuseColor = [1.0, 1.0, 1.0]
off_and_on("single")
# The pass's count of actors with lines (the GUI shows the view's line
# settings while it is above 0) is the most any process holds: a line on
# the last process alone still counts on rank 0. Control: a sphere alone
# counts 0. (Without the reduction rank 0 said 0 with 2 ranks: run by hand.)
Hide(single, view)
lastOnly = ProgrammableSource(OutputDataSetType="vtkPolyData")
lastOnly.Script = (
    "from vtkmodules.vtkCommonCore import vtkPoints\n"
    "from vtkmodules.vtkCommonDataModel import vtkCellArray\n"
    "from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline as sddp\n"
    "info = self.GetOutputInformation(0)\n"
    "piece = info.Get(sddp.UPDATE_PIECE_NUMBER()) if info.Has(sddp.UPDATE_PIECE_NUMBER()) else 0\n"
    "pieces = info.Get(sddp.UPDATE_NUMBER_OF_PIECES()) if info.Has(sddp.UPDATE_NUMBER_OF_PIECES()) else 1\n"
    "points, cells = vtkPoints(), vtkCellArray()\n"
    "if piece == pieces - 1:\n"
    "    cells.InsertNextCell(2)\n"
    "    cells.InsertCellPoint(points.InsertNextPoint(-1.2, 0.3, 0.5))\n"
    "    cells.InsertCellPoint(points.InsertNextPoint(1.2, 0.3, 0.5))\n"
    "out = self.GetOutput()\n"
    "out.SetPoints(points)\n"
    "out.SetLines(cells)\n")


def line_actors_in_view():
    Render(view)
    return pas.GetNumberOfLineActors()


check(line_actors_in_view() == 0, "a sphere alone: the pass counts 0 actors with lines")
Show(lastOnly, view)
counted = line_actors_in_view()
check(counted == 1, "a line on the last of %d processes alone: rank 0's pass counts %d actors with lines (1)" % (ranks, counted))
Hide(lastOnly, view)
# ParaView's own AO (Use Ambient Occlusion) stays on while no lines get
# line AO, and is off on every process from the first frame in which lines
# on any process do: with the line on the last process alone, rank 0 (no
# lines of its own, none in its last frame) must not darken its pieces with
# it. A plane on rank 0 alone (a Plane source is not split) under the split
# sphere shows ParaView's AO. Control: with the view deciding by this
# process's count alone, the first frame with the line differed from the
# second on 2 processes (run by hand).
floor = Plane(Origin=[-1.2, -1.0, -0.45], Point1=[1.8, -1.0, -0.45], Point2=[-1.2, 1.0, -0.45])
floorDisplay = Show(floor, view)
floorDisplay.DiffuseColor = [1.0, 1.0, 1.0]
view.SurfaceAOMethod = "None"
view.LineAOMethod = "Voxelized Lines"
view.UseAmbientOcclusion = 0
plain = read(grey("ssao-off"))
view.UseAmbientOcclusion = 1
theirs = read(grey("ssao-on"))
check(apart(plain, theirs) > 0.005,
      "no lines anywhere: ParaView's own AO applies (%.2f%% of pixels more than 8 levels apart from it off)"
      % (100 * apart(plain, theirs)))
Show(lastOnly, view)
first = read(grey("ssao-lines-first"))
second = read(grey("ssao-lines-second"))
check(apart(first, second) == 0,
      "the first frame with a line on the last of %d processes has no ParaView AO on any process, as the "
      "second: %.2f%% of pixels more than 8 levels apart" % (ranks, 100 * apart(first, second)))
view.UseAmbientOcclusion = 0
Hide(lastOnly, view)
Hide(floor, view)
with open(os.path.join(outdir, "np%d-reports.json" % ranks), "w") as f:
    json.dump(reports, f)
print("rank 0's report (lines and sphere): %s" % json.dumps(reports["both"]))
sys.stdout.flush()

for name in ("lines", "both"):
    lineReport = reports[name].get("lines", {})
    check(lineReport.get("pixels", 0) > 500 and lineReport.get("segments_of_all_processes") == 36 * 60,
          "%s: rank 0's lines get line AO (%s line pixels) from a grid of every process's %s segments (36 x 60)"
          % (name, lineReport.get("pixels"), lineReport.get("segments_of_all_processes")))
check(reports["lines-gl"].get("lines", {}).get("ao") == "OpenGL",
      "with the OpenGL backend the prisms run on the window's OpenGL (report: %s)"
      % reports["lines-gl"].get("lines", {}).get("ao"))
check(reports["single"].get("lines", {}).get("segments_of_all_processes") == 40,
      "one line source: its 40 segments in the grid (report: %s)"
      % reports["single"].get("lines", {}).get("segments_of_all_processes"))
if ranks > 1:
    mine = reports["lines"].get("lines", {}).get("segments", 0)
    check(0 < mine < 36 * 60, "the lines are split: rank 0 holds %d of the %d segments" % (mine, 36 * 60))
    check(reports["both"].get("lines", {}).get("occlude_surfaces") is True,
          "on %d processes the sphere's grid holds every process's lines (occlude_surfaces)" % ranks)


    # (lines-gl: this run's OpenGL prisms against the serial CPU picture.)
    for name, serialName, offName in (("lines", "lines", "lines-off"), ("both", "both", "both-off"),
                                      ("lines-gl", "lines", "lines-off"), ("single", "single", "single-off")):
        serial = read(os.path.join(outdir, "np1-%s.png" % serialName))
        here = read(os.path.join(outdir, "np%d-%s.png" % (ranks, name)))
        serialOff = read(os.path.join(outdir, "np1-%s.png" % offName))
        hereOff = read(os.path.join(outdir, "np%d-%s.png" % (ranks, offName)))
        # (Without AO a few pixels where tubes of both processes touch at
        # one depth differ: the compositor's tie, 4 pixels seen.)
        check(apart(serialOff, hereOff) < 0.001,
              "%s: the pictures without AO agree: %.3f%% of pixels more than 8 levels apart (bound 0.1%%)"
              % (name, 100 * apart(serialOff, hereOff)))
        ratio = (serialOff - here).clip(min=0).sum() / (serialOff - serial).clip(min=0).sum()
        # The bound: the grid's plan and radius come from sums over the
        # segments in another order (rank by rank), a rounding apart; the
        # pictures agree but for pixels where a line of one process passes
        # over another's (each process's G-buffer sees its own lines only).
        check(apart(serial, here) < 0.005 and 0.98 <= ratio <= 1.02,
              "%s on %d processes gives the serial picture: %.2f%% of pixels more than 8 levels apart (bound "
              "0.5%%; largest %.1f), %.3f of the serial darkening (bound 0.98..1.02)"
              % (name, ranks, 100 * apart(serial, here), abs(serial - here).max(), ratio))
finish()

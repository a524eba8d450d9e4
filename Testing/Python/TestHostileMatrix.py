"""A matrix of hostile but realistic inputs against every `cao` subcommand:
damaged files of every format the tool reads (volumes and meshes: cut
short at several lengths, bytes overwritten in the header, the sizes in a
text header made huge, negative, zero or not a number, garbage appended,
empty) and absurd option values (NaN, infinities, negative, zero, huge,
not a number, empty) for the numeric options of lao, carve, tf, render and
surface.

Every case runs in its own process and must end in one of two ways:
  - exit 0 (the input is usable as it is), or
  - exit 2 with one line "cao: error: ..." last on stderr,
and never: a signal (a crash or an abort), a timeout (60 s), more than
4 GiB of resident memory (a runaway), a VTK log line (ERR| / WARN|), VTK's
"ERROR: In" text, an uncaught exception ("terminate called"). Values that
are not numbers (NaN, inf, "abc", "") must be refused: accepting them is a
silent result. The undamaged files and the default options are the
negative controls: they must exit 0 (so the matrix does not pass by
refusing everything).

The plugin's readers (.slc, NIfTI) and the LAO filter run in pvpython on
the same damaged volumes (CAO_PVPYTHON, CAO_PLUGIN): no signal, no
allocation abort, voxels from the files as written, none from an empty one.

Prints one line per failing case and a table of outcomes; exit 1 on any
failure. Environment: CAO_TOOL, CAO_DATA_DIR, CAO_PVPYTHON, CAO_PLUGIN."""
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkFiltersCore import vtkTriangleFilter
from vtkmodules.vtkIOGeometry import vtkOBJWriter, vtkSTLWriter
from vtkmodules.vtkIOImage import vtkMetaImageWriter, vtkNIFTIImageWriter, vtkSLCReader
from vtkmodules.vtkIOLegacy import vtkPolyDataWriter, vtkStructuredPointsWriter
from vtkmodules.vtkIOPLY import vtkPLYWriter
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter, vtkXMLPolyDataWriter
from vtkmodules.vtkImagingCore import vtkImageShrink3D

tool = os.environ["CAO_TOOL"]
data = os.environ["CAO_DATA_DIR"]
tmp = tempfile.mkdtemp(prefix="cao-matrix-")
MEMORY_LIMIT_KIB = 4 * 1024 * 1024
failures = []
outcomes = {}


def path(name):
    return os.path.join(tmp, name)


# ---------------------------------------------------------------- sources
# A small volume (neghip shrunk to 32^3) in every volume format, and a
# sphere in every mesh format: the undamaged sources.
slc = vtkSLCReader()
slc.SetFileName(os.path.join(data, "neghip.slc"))
shrink = vtkImageShrink3D()
shrink.SetInputConnection(slc.GetOutputPort())
shrink.SetShrinkFactors(2, 2, 2)
shrink.Update()
image = shrink.GetOutput()

volumes = {}


def written(data_object, into):
    """A writer of `data_object` into the dict `into`: name, writer, setup."""
    def write(name, writer, configure=None):
        writer.SetInputData(data_object)
        writer.SetFileName(path(name))
        if configure:
            configure(writer)
        writer.Write()
        into[name] = path(name)
    return write


volume_writer = written(image, volumes)


volume_writer("ascii.vti", vtkXMLImageDataWriter(), lambda w: w.SetDataModeToAscii())
volume_writer("binary.vti", vtkXMLImageDataWriter(), lambda w: (w.SetDataModeToBinary(),
                                                                w.SetCompressorTypeToNone()))
volume_writer("appended.vti", vtkXMLImageDataWriter(), lambda w: (w.SetDataModeToAppended(),
                                                                  w.EncodeAppendedDataOff(),
                                                                  w.SetCompressorTypeToNone()))
volume_writer("zlib.vti", vtkXMLImageDataWriter(), lambda w: w.SetDataModeToAppended())
volume_writer("local.mha", vtkMetaImageWriter(), lambda w: w.SetCompression(False))
mhd = vtkMetaImageWriter()
mhd.SetInputData(image)
mhd.SetFileName(path("split.mhd"))
mhd.SetRAWFileName(path("split.raw"))
mhd.SetCompression(False)
mhd.Write()
volumes["split.mhd"] = path("split.mhd")
volume_writer("plain.nii", vtkNIFTIImageWriter())
volume_writer("packed.nii.gz", vtkNIFTIImageWriter())
volume_writer("ascii.vtk", vtkStructuredPointsWriter(), lambda w: w.SetFileTypeToASCII())
volume_writer("binary.vtk", vtkStructuredPointsWriter(), lambda w: w.SetFileTypeToBinary())
shutil.copy(os.path.join(data, "neghip.slc"), path("neghip.slc"))
volumes["neghip.slc"] = path("neghip.slc")

sphere = vtkSphereSource()
sphere.SetRadius(8.0)
sphere.SetCenter(32, 32, 32)
sphere.SetThetaResolution(16)
sphere.SetPhiResolution(12)
triangles = vtkTriangleFilter()
triangles.SetInputConnection(sphere.GetOutputPort())
triangles.Update()
mesh = triangles.GetOutput()
meshes = {}
mesh_writer = written(mesh, meshes)


mesh_writer("ascii.stl", vtkSTLWriter(), lambda w: w.SetFileTypeToASCII())
mesh_writer("binary.stl", vtkSTLWriter(), lambda w: w.SetFileTypeToBinary())
mesh_writer("ascii.ply", vtkPLYWriter(), lambda w: w.SetFileTypeToASCII())
mesh_writer("binary.ply", vtkPLYWriter(), lambda w: w.SetFileTypeToBinary())
mesh_writer("mesh.vtp", vtkXMLPolyDataWriter())
mesh_writer("ascii.vtp", vtkXMLPolyDataWriter(), lambda w: w.SetDataModeToAscii())
mesh_writer("mesh.obj", vtkOBJWriter())
mesh_writer("ascii-mesh.vtk", vtkPolyDataWriter(), lambda w: w.SetFileTypeToASCII())
mesh_writer("binary-mesh.vtk", vtkPolyDataWriter(), lambda w: w.SetFileTypeToBinary())


# ---------------------------------------------------------------- damage
def damaged(source):
    """(tag, bytes) variants of a file."""
    content = open(source, "rb").read()
    n = len(content)
    out = [("empty", b"")]
    for share in (0.01, 0.1, 0.5, 0.9, 0.99):
        out.append(("cut %d%%" % round(100 * share), content[:max(1, int(n * share))]))
    out.append(("garbage appended", content + bytes(range(256)) * 4))
    # Bytes overwritten in the first 512 (the header, for every format).
    for seed, value in ((1, 0xFF), (2, 0x00), (3, 0x7F)):
        b = bytearray(content)
        for i in range(seed * 7, min(n, 512), 37):
            b[i] = value
        out.append(("header bytes 0x%02X" % value, bytes(b)))
    # The sizes in a text header: huge, negative, zero, not a number.
    head = content[:4096]
    tail = content[4096:]
    for tag, repl in (("sizes huge", b"99999999"), ("sizes negative", b"-7"),
                      ("sizes zero", b"0"), ("sizes NaN", b"nan")):
        text, count = re.subn(rb"(?<=[ =\"])(32|33|64|65)(?=[ \"\n\r])", repl, head)
        if count:
            out.append((tag, text + tail))
    return out


def run_measured(args):
    """As run, with the child's peak resident memory from wait4."""
    start = time.monotonic()
    p = subprocess.Popen([tool] + args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                         cwd=tmp)
    err = b""
    deadline = start + 60
    # Read stderr while waiting (a full pipe would block the child).
    import selectors
    sel = selectors.DefaultSelector()
    sel.register(p.stderr, selectors.EVENT_READ)
    chunks = []
    timed_out = False
    while True:
        left = deadline - time.monotonic()
        if left <= 0:
            p.kill()
            timed_out = True
            break
        # The child closing stderr (its end) ends the loop; wait4 reaps it
        # below (poll here could reap it first).
        if sel.select(timeout=min(left, 1.0)):
            chunk = p.stderr.read1(65536)
            if not chunk:
                break
            chunks.append(chunk)
    rest = p.stderr.read()
    if rest:
        chunks.append(rest)
    _, status, usage = os.wait4(p.pid, 0)
    p.returncode = os.waitstatus_to_exitcode(status)
    err = b"".join(chunks).decode(errors="replace")
    if timed_out:
        return "timeout", err, time.monotonic() - start, usage.ru_maxrss
    return p.returncode, err, time.monotonic() - start, usage.ru_maxrss


def judge(case, args, must_refuse=False, must_run=False):
    rc, err, seconds, rss = run_measured(args)
    lines = [l for l in err.splitlines() if l.strip()]
    problems = []
    if rc == "timeout":
        kind = "slow"
        problems.append("no end within 60 s")
    elif rc < 0 or rc >= 128:
        kind = "crash"
        problems.append("signal %d" % (-rc if rc < 0 else rc - 128))
    elif rss > MEMORY_LIMIT_KIB:
        kind = "runaway"
        problems.append("%d MiB resident" % (rss // 1024))
    elif rc not in (0, 2):
        kind = "unclear"
        problems.append("exit %d" % rc)
    elif rc == 2 and not (lines and lines[-1].startswith("cao: error: ")):
        kind = "unclear"
        problems.append("the last line is not 'cao: error: ...'")
    elif any(w in err for w in ("ERR|", "WARN|", "ERROR: In", "terminate called",
                                "Segmentation", "Unable to allocate")):
        kind = "unclear"
        problems.append("VTK or runtime output on stderr")
    elif rc == 0 and "cao: error:" in err:
        kind = "unclear"
        problems.append("an error printed, exit 0")
    elif rc == 0 and must_refuse:
        kind = "silent"
        problems.append("accepted")
    elif rc != 0 and must_run:
        kind = "control refused"
        problems.append("a valid input was refused")
    else:
        kind = "ok (exit %d)" % rc
    outcomes[kind] = outcomes.get(kind, 0) + 1
    if problems:
        failures.append(case)
        print("FAIL: %s: %s; %s: %s" % (case, ", ".join(problems), " ".join(args)[:160],
                                        (lines[-1] if lines else "")[:200]))
    return rc


# ---------------------------------------------------------------- files
volume = path("neghip.slc")
for name, source in sorted(volumes.items()):
    judge("volume %s as written" % name, ["lao", source, "--rays", "6"], must_run=True)
    for tag, content in damaged(source):
        damaged_path = path("damaged-" + name)
        with open(damaged_path, "wb") as f:
            f.write(content)
        # (A split .mhd's header is damaged here; its data file below.)
        judge("volume %s, %s: lao" % (name, tag), ["lao", damaged_path, "--rays", "6"],
              must_refuse=tag in ("empty",))
        if tag in ("cut 50%", "sizes huge", "header bytes 0xFF"):
            judge("volume %s, %s: carve" % (name, tag),
                  ["carve", damaged_path, "--rays", "6", "--path", "2"],
                  must_refuse=False)
raw = path("split.raw")
content = open(raw, "rb").read()
for share in (0.0, 0.5, 0.99):
    with open(path("cut.raw"), "wb") as f:
        f.write(content[:int(len(content) * share)])
    with open(path("cut.mhd"), "w") as f:
        f.write(open(path("split.mhd")).read().replace("split.raw", "cut.raw"))
    judge("volume split.mhd, its data file cut to %d%%" % round(100 * share),
          ["lao", path("cut.mhd"), "--rays", "6"], must_refuse=True)

for name, source in sorted(meshes.items()):
    judge("mesh %s as written: carve" % name,
          ["carve", volume, "--mesh", source, "--rays", "6", "--path", "2"], must_run=True)
    judge("mesh %s as written: surface" % name,
          ["surface", source, "--image", "48x48", "--method", "none", "-o", path("s.png")],
          must_run=True)
    for tag, content in damaged(source):
        damaged_path = path("damaged-" + name)
        with open(damaged_path, "wb") as f:
            f.write(content)
        judge("mesh %s, %s: carve" % (name, tag),
              ["carve", volume, "--mesh", damaged_path, "--rays", "6", "--path", "2"],
              must_refuse=tag == "empty")
        judge("mesh %s, %s: surface" % (name, tag),
              ["surface", damaged_path, "--image", "48x48", "--method", "none", "-o",
               path("s.png")], must_refuse=tag == "empty")

# ---------------------------------------------------------------- options
NOT_NUMBERS = ["nan", "inf", "-inf", "abc", ""]
NUMBERS = ["-1", "0", "1e308", "1e-308", "2147483648", "-2147483649"]
commands = {
    "lao": (["lao", volume, "--rays", "6"],
            ["--reach", "--samples", "--density", "--offset", "--unit-distance", "--threads",
             "--component"]),
    "carve": (["carve", volume, "--rays", "6", "--path", "2"],
              ["--reach", "--density", "--size", "--path", "--layers", "--aa", "--threads"]),
    "tf": (["tf", volume, "--rays", "6", "--from", "0,0,255,0.8", "--to", "0,0,255,0.5"],
           ["--reach", "--density", "--threads"]),
    "surface": (["surface", meshes["mesh.vtp"], "--image", "48x48", "-o", path("o.png")],
                ["--radius", "--slices", "--zoom", "--azimuth", "--elevation"]),
    "surface --method volumetric": (["surface", meshes["mesh.vtp"], "--image", "48x48", "--method", "volumetric",
                              "-o", path("o.png")], ["--samples", "--radius"]),
    "render": (["render", volume, "--image", "48x48", "--path", "1", "--rays", "6", "-o",
                path("r_%d.png")],
               ["--zoom", "--ao-strength", "--sample-distance", "--azimuth"]),
}
for command, (base, options) in commands.items():
    judge("%s with its defaults" % command, base, must_run=True)
    for option in options:
        values = NOT_NUMBERS + (NUMBERS if command != "render" else ["-1", "0", "1e308"])
        for value in values:
            judge("%s %s '%s'" % (command, option, value), base + [option, value],
                  must_refuse=value in NOT_NUMBERS)
# Lists and poses.
for value in ("0,0,255,5", "0,0,255", "nan,0,255,1", "0,-1,255,1", "", "1,2,3,4,5,6"):
    judge("lao --opacity '%s'" % value, ["lao", volume, "--rays", "6", "--opacity", value],
          must_refuse=True)
for value in ("1 2", "nan 0 0", "0 0 0 0 0 0 -1", "0 0 0 0 0 0 0", "inf 0 0", "a b c",
              "0 0 0 1e308 0 0"):
    judge("carve --pose '%s'" % value, ["carve", volume, "--rays", "6", "--pose", value],
          must_refuse=value != "0 0 0 1e308 0 0")
for value in ("7", "fib:0", "fib:65537", "fib:-1", "fib:x", "", "6,", ",6", "rubiks", "54x"):
    judge("lao --rays '%s'" % value, ["lao", volume, "--rays", value], must_refuse=True)

# ---------------------------------------------------------------- pvpython
# The plugin's readers (.slc, .nii, .nii.gz) and the LAO filter in pvpython,
# on the same damaged files: no signal, no allocation abort; a file as
# written gives voxels, an empty one none.
PV = r'''
import sys
from paraview.simple import *
LoadPlugin(sys.argv[1], remote=False, ns=globals())
reader = OpenDataFile(sys.argv[2])
lao = LocalAmbientOcclusion(Input=reader)
lao.Backend = "CPU"
lao.UpdatePipeline()
print("POINTS", lao.GetDataInformation().GetNumberOfPoints())
'''
pvpython = os.environ.get("CAO_PVPYTHON", "")
plugin = os.environ.get("CAO_PLUGIN", "")
if pvpython and plugin:
    script = path("pv_case.py")
    with open(script, "w") as f:
        f.write(PV)
    for name in ("neghip.slc", "plain.nii", "packed.nii.gz"):
        variants = [("as written", open(volumes[name], "rb").read())] + damaged(volumes[name])
        for tag, content in variants:
            damaged_path = path("pv-" + name)
            with open(damaged_path, "wb") as f:
                f.write(content)
            case = "pvpython: %s, %s" % (name, tag)
            try:
                p = subprocess.run([pvpython, "--force-offscreen-rendering", script, plugin,
                                    damaged_path], capture_output=True, text=True, timeout=120)
                rc, text = p.returncode, p.stdout + p.stderr
            except subprocess.TimeoutExpired:
                rc, text = "timeout", ""
            points = [int(l.split()[1]) for l in (p.stdout if rc != "timeout" else "").splitlines()
                      if l.startswith("POINTS")]
            problems = []
            if rc == "timeout":
                kind = "slow"
                problems.append("no end within 120 s")
            elif rc < 0 or rc >= 128:
                kind = "crash"
                problems.append("signal %d" % (-rc if rc < 0 else rc - 128))
            elif rc != 0 and not (rc == 1 and re.search(r"^\w+Error: .+", text, re.M)):
                # pvpython ends with 1 on a Python exception: ParaView's own
                # "No reader found for ..." is a clear refusal.
                kind = "unclear"
                problems.append("exit %d without an exception's message" % rc)
            elif any(w in text for w in ("Unable to allocate", "terminate called", "Segmentation")):
                kind = "crash"
                problems.append("an abort or allocation failure in the output")
            elif tag == "as written" and not (rc == 0 and points and points[0] > 0):
                kind = "control refused"
                problems.append("the file as written gave no voxels")
            elif tag == "empty" and points and points[0] > 0:
                kind = "silent"
                problems.append("an empty file gave voxels")
            else:
                kind = "ok (pvpython)"
            outcomes[kind] = outcomes.get(kind, 0) + 1
            if problems:
                failures.append(case)
                print("FAIL: %s: %s" % (case, ", ".join(problems)))
else:
    print("no CAO_PVPYTHON or CAO_PLUGIN: the pvpython cases did not run")
    if os.environ.get("CAO_REQUIRE_PVPYTHON"):
        failures.append("pvpython required")

total = sum(outcomes.values())
print("\n| outcome | cases |\n|---|---:|")
for kind in sorted(outcomes):
    print("| %s | %d |" % (kind, outcomes[kind]))
print("| all | %d |" % total)
shutil.rmtree(tmp, ignore_errors=True)
if total < 400:
    print("FAIL: the matrix has %d cases, fewer than 400" % total)
    sys.exit(1)
if failures:
    print("%d of %d cases failed" % (len(failures), total))
    sys.exit(1)
print("all %d cases ended cleanly" % total)

"""Headers that claim more than their files hold, through `cao` and through
pvpython with the plugin: each is refused with one clear error that names
the file and the limit, and nothing aborts (no signal, no "Unable to
allocate" from VTK).

The files: an ASCII .vti claiming 100000^3 points and one claiming 1000^3
with a few bytes of data; an .slc claiming 100000^3 voxels, one whose raw
slices stop after 10 bytes, one whose run-length stream runs past its slice;
a .nii and a .nii.gz claiming 30000^3 voxels and a .nii claiming 512^3
16-bit voxels with no data; a binary STL claiming 10^9 triangles; a .mhd
claiming 100000^3 (through `cao`). Negative controls: valid files of every
kind (the same writers, real sizes) read and run.

Not covered, and not coverable by the plugin: ParaView's own MetaImage
reader with such a header aborts inside ParaView when a filter is created
on it (paraview.simple gathers the reader's data information, which runs
the reader, before the filter exists); the LAO filters refuse a declared
extent above the limit in their information pass and request nothing
upstream, which holds for pipelines driven from VTK.

Environment: CAO_TOOL, CAO_DATA_DIR; CAO_PVPYTHON and CAO_PLUGIN for the
ParaView half (it is required when CAO_PVPYTHON is set)."""
import gzip
import os
import struct
import subprocess
import sys
import tempfile

from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkIOGeometry import vtkSTLWriter
from vtkmodules.vtkIOImage import vtkNIFTIImageWriter, vtkSLCReader
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter

tool = os.environ["CAO_TOOL"]
data = os.environ["CAO_DATA_DIR"]
pvpython = os.environ.get("CAO_PVPYTHON", "")
plugin = os.environ.get("CAO_PLUGIN", "")
tmp = tempfile.mkdtemp(prefix="cao-hostile-")
failures = []
passed = 0


def check(ok, what):
    global passed
    if ok:
        passed += 1
    else:
        failures.append(what)
    print(("ok: " if ok else "FAIL: ") + what)


def path(name):
    return os.path.join(tmp, name)


def write(name, content):
    with open(path(name), "wb") as f:
        f.write(content)
    return path(name)


# --- The hostile files -----------------------------------------------------
VTI = ('<?xml version="1.0"?>\n<VTKFile type="ImageData" version="0.1" byte_order="LittleEndian">\n'
       '<ImageData WholeExtent="0 {n} 0 {n} 0 {n}" Origin="0 0 0" Spacing="1 1 1">\n'
       '<Piece Extent="0 {n} 0 {n} 0 {n}"><PointData Scalars="s">\n'
       '<DataArray type="UInt8" Name="s" format="ascii">0 1 2 3</DataArray>\n'
       '</PointData></Piece></ImageData></VTKFile>\n')
huge_vti = write("huge.vti", VTI.format(n=99999).encode())
short_vti = write("short.vti", VTI.format(n=999).encode())

SLC = "11111\n{n} {n} {n} 8\n1 1 1\n2 0 0\n{c}\n0 0 X"
huge_slc = write("huge.slc", SLC.format(n=100000, c=0).encode())
short_slc = write("short.slc", SLC.format(n=64, c=0).encode() + bytes(10))
# One run-length slice of an 8^3 volume: a run of 127 copies (8*8 = 64 voxels).
overrun_slc = write("overrun.slc", SLC.format(n=8, c=1).encode() + b"3 X" + bytes([127, 5, 0]))


def nifti1(dims, datatype=2, bitpix=8, data=b""):
    h = bytearray(348)
    struct.pack_into("<i", h, 0, 348)
    struct.pack_into("<8h", h, 40, len(dims), *dims, *([1] * (7 - len(dims))))
    struct.pack_into("<hh", h, 70, datatype, bitpix)
    struct.pack_into("<8f", h, 76, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0)
    struct.pack_into("<f", h, 108, 352.0)
    h[344:348] = b"n+1\0"
    return bytes(h) + bytes(4) + data


huge_nii = write("huge.nii", nifti1([30000, 30000, 30000]))
huge_nii_gz = write("huge.nii.gz", gzip.compress(nifti1([30000, 30000, 30000])))
short_nii = write("short.nii", nifti1([512, 512, 512], datatype=4, bitpix=16))
huge_stl = write("huge.stl", bytes(80) + struct.pack("<I", 10 ** 9) + bytes(50))
huge_mhd = write("huge.mhd", b"ObjectType = Image\nNDims = 3\nDimSize = 100000 100000 100000\n"
                 b"ElementType = MET_UCHAR\nElementDataFile = LOCAL\n" + bytes(16))

# --- Valid files of the same kinds (negative controls) ----------------------
slc = vtkSLCReader()
slc.SetFileName(os.path.join(data, "neghip.slc"))
slc.Update()
good_nii, good_nii_gz, good_vti = path("good.nii"), path("good.nii.gz"), path("good.vti")
for name in (good_nii, good_nii_gz):
    w = vtkNIFTIImageWriter()
    w.SetInputConnection(slc.GetOutputPort())
    w.SetFileName(name)
    w.Write()
w = vtkXMLImageDataWriter()
w.SetInputConnection(slc.GetOutputPort())
w.SetDataModeToAscii()
w.SetFileName(good_vti)
w.Write()
good_stl = path("good.stl")
sphere = vtkSphereSource()
sphere.SetRadius(10.0)
sphere.SetCenter(33.0, 33.0, 33.0)
w = vtkSTLWriter()
w.SetInputConnection(sphere.GetOutputPort())
w.SetFileTypeToBinary()
w.SetFileName(good_stl)
w.Write()


def run(args):
    p = subprocess.run([tool, *args], capture_output=True, text=True, timeout=900)
    return p.returncode, p.stdout, p.stderr


def refused(args, words, what):
    rc, out, err = run(args)
    lines = [l for l in err.strip().splitlines() if l.strip()]
    check(rc > 0 and len(lines) >= 1 and lines[0].startswith("cao: error:") and
          all(w in lines[0] for w in words) and "Unable to allocate" not in err and "ERR|" not in err,
          "%s: refused with one clear line (rc=%d): %r" % (what, rc, lines[:2]))


for f, words in ((huge_vti, ["huge.vti", "100000 x 100000", "2147483647"]),
                 (short_vti, ["short.vti", "1000 x 1000 x 1000", "short"]),
                 (huge_slc, ["huge.slc", "100000", "2147483647"]),
                 (short_slc, ["short.slc", "slice 0 of 64"]),
                 (overrun_slc, ["overrun.slc", "runs past"]),
                 (huge_nii, ["huge.nii", "30000", "2147483647"]),
                 (huge_nii_gz, ["huge.nii.gz", "30000", "2147483647"]),
                 (short_nii, ["short.nii", "512 x 512 x 512", "short"]),
                 (huge_mhd, ["huge.mhd", "100000", "2147483647"])):
    refused(["lao", f, "--threads", "2"], words, "cao lao " + os.path.basename(f))
refused(["carve", os.path.join(data, "neghip.slc"), "--mesh", huge_stl, "--path", "1"],
        ["huge.stl", "1000000000 triangles", "short"], "cao carve --mesh huge.stl")
refused(["surface", huge_stl, "--method", "none", "--image", "32x32", "-o", path("s.png")],
        ["huge.stl", "1000000000 triangles"], "cao surface huge.stl")

# A frame larger than the machine can hold: refused up front with the need
# and the memory (it ended in std::bad_alloc).
memory = os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
if 100.0 * 16384 * 16384 > 0.8 * memory:
    refused(["surface", os.path.join(data, "Bunny.vtp"), "--method", "none", "--image", "16384x16384",
             "-o", path("s.png")], ["16384x16384", "GB", "80%"], "cao surface --image 16384x16384")
else:
    print("this machine has %.0f GB: a 16384^2 frame fits, its refusal is not checked" % (memory / 1e9))

for f in (good_vti, good_nii, good_nii_gz, os.path.join(data, "neghip.slc")):
    rc, out, err = run(["lao", f, "--threads", "2", "--json"])
    check(rc == 0, "negative control: cao lao %s reads it (rc=%d %s)" % (os.path.basename(f), rc, err.strip()[:200]))
rc, out, err = run(["carve", os.path.join(data, "neghip.slc"), "--mesh", good_stl, "--path", "1", "--json"])
check(rc == 0, "negative control: a binary STL of real size clips (rc=%d %s)" % (rc, err.strip()[:200]))

# --- VTK pipelines: VTK's own readers into the LAO filters ------------------
# The filters refuse a declared extent above the limit in their information
# pass and request nothing upstream: VTK's MetaImage reader then allocates
# nothing. The plugin's readers (vtkCAOSLCReader, vtkCAONIfTIReader) refuse
# in both passes. Each case runs in its own process, so an abort shows.
VTKCASE = r'''
import sys
from vtkmodules.vtkIOImage import vtkMetaImageReader
from vtkmodules.vtkFiltersSources import vtkSphereSource
from contextualao import (vtkCAOSLCReader, vtkClipDepthMaps, vtkContextualAmbientOcclusion,
                          vtkLocalAmbientOcclusion)
kind, name = sys.argv[1], sys.argv[2]
reader = vtkCAOSLCReader() if kind == "slc" else vtkMetaImageReader()
reader.SetFileName(name)
f = vtkContextualAmbientOcclusion() if kind == "cao" else vtkLocalAmbientOcclusion()
f.SetInputConnection(reader.GetOutputPort())
if kind == "cao":
    sphere = vtkSphereSource()
    maps = vtkClipDepthMaps()
    maps.SetInputConnection(sphere.GetOutputPort())
    f.SetInputConnection(1, maps.GetOutputPort())
f.SetBackendToCPU()
ok = f.GetExecutive().Update()
print("UPDATE", ok, f.GetOutput().GetNumberOfPoints() if f.GetOutput() else -1)
'''
vtkcase = write("vtk_case.py", VTKCASE.encode())
for kind, f, words in (("lao", huge_mhd, "2147483647"), ("cao", huge_mhd, "2147483647"),
                       ("slc", huge_slc, "huge.slc")):
    p = subprocess.run([sys.executable, vtkcase, kind, f], capture_output=True, text=True, timeout=300)
    text = p.stdout + p.stderr
    check(p.returncode == 0 and words in text and "UPDATE 0" in p.stdout and "Unable to allocate" not in text,
          "VTK pipeline, %s into %s: refused (%r), no allocation, no abort (rc=%d)"
          % (os.path.basename(f), "the plugin's SLC reader and the LAO" if kind == "slc" else kind, words,
             p.returncode))

# --- pvpython with the plugin ----------------------------------------------
PV = r'''
import sys
from paraview.simple import *
LoadPlugin(sys.argv[1], remote=False, ns=globals())
from paraview import servermanager
name, kind = sys.argv[2], sys.argv[3]
reader = OpenDataFile(name)
print("READER", reader.GetXMLName())
lao = LocalAmbientOcclusion(Input=reader)
lao.Backend = "CPU"
lao.UpdatePipeline()
info = lao.GetDataInformation()
print("POINTS", info.GetNumberOfPoints())
'''
script = write("pv_case.py", PV.encode())
if not pvpython:
    print("no CAO_PVPYTHON: the ParaView half did not run")
else:
    for f, kind, words in ((huge_slc, "slc", "huge.slc"), (overrun_slc, "slc", "runs past"),
                           (huge_nii, "nii", "huge.nii"), (huge_nii_gz, "nii", "huge.nii.gz"),
                           (short_nii, "nii", "short"),
                           (good_nii, "good", None), (os.path.join(data, "neghip.slc"), "good", None)):
        p = subprocess.run([pvpython, "--force-offscreen-rendering", script, plugin, f, kind],
                           capture_output=True, text=True, timeout=600)
        text = p.stdout + p.stderr
        points = [l for l in p.stdout.splitlines() if l.startswith("POINTS")]
        if words is None:
            check(p.returncode == 0 and points and points[0] != "POINTS 0",
                  "negative control: pvpython reads %s through the plugin and runs the LAO (rc=%d, %s)"
                  % (os.path.basename(f), p.returncode, points))
        else:
            check(p.returncode == 0 and words in text and "Unable to allocate" not in text and
                  (not points or points[0] == "POINTS 0"),
                  "pvpython, %s through the plugin and the LAO filter: an error naming %r, no abort "
                  "(rc=%d; %s)" % (os.path.basename(f), words, p.returncode,
                                  " | ".join(l for l in text.splitlines() if "ERR" in l or "rror" in l)[:300]))

print("%d passed, %d failed" % (passed, len(failures)))
sys.exit(1 if failures else 0)

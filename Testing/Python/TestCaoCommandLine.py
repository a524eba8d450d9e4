"""The `cao` tool end to end: every volume and mesh format it promises,
poses from the command line and from a file, --json, --verify (exact at
every pose), the .vti it writes, and clear errors with non-zero exit codes
for unreadable files, bad arguments and bad clip meshes."""
import json
import re
import os
import subprocess
import sys
import tempfile

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkIOGeometry import vtkSTLWriter
from vtkmodules.vtkIOImage import vtkNIFTIImageWriter, vtkSLCReader
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLPolyDataWriter

tool = os.environ["CAO_TOOL"]
data = os.environ["CAO_DATA_DIR"]
tmp = tempfile.mkdtemp(prefix="cao-cli-")
failures = []
passed = 0


def run(*args):
    p = subprocess.run([tool, *args], capture_output=True, text=True, timeout=600)
    return p.returncode, p.stdout, p.stderr


def check(condition, what):
    global passed
    if condition:
        passed += 1
    else:
        failures.append(what)
        print("FAIL:", what)


def expect_error(args, code, words, what):
    rc, out, err = run(*args)
    check(rc == code and words in err and "Segmentation" not in err,
          f"{what}: rc={rc} stderr={err.strip()[:200]!r}")


# lao on three formats: .slc, .mhd, .vti, legacy .vtk, and a .nii we write.
nii = os.path.join(tmp, "neghip.nii.gz")
r = vtkSLCReader()
r.SetFileName(os.path.join(data, "neghip.slc"))
w = vtkNIFTIImageWriter()
w.SetInputConnection(r.GetOutputPort())
w.SetFileName(nii)
w.Write()
for volume in ("neghip.slc", "HeadMRVolume.mhd", "hydrogen.vti", "ironProt.vtk", nii):
    path = volume if os.path.isabs(volume) else os.path.join(data, volume)
    rc, out, err = run("lao", path, "--rays", "6", "--json")
    ok = rc == 0
    if ok:
        summary = json.loads(out)
        ok = 0.0 <= summary["ao_range"][0] <= summary["ao_range"][1] <= 1.0
    check(ok, f"lao {volume}: rc={rc} {err.strip()[:200]}")

# lao writes a .vti with the AO array.
out_vti = os.path.join(tmp, "lao.vti")
rc, out, err = run("lao", os.path.join(data, "neghip.slc"), "--rays", "fib:20", "-o", out_vti)
reader = vtkXMLImageDataReader()
reader.SetFileName(out_vti)
reader.Update()
ao = reader.GetOutput().GetPointData().GetArray("AmbientOcclusion")
check(rc == 0 and ao is not None and ao.GetNumberOfTuples() == 66 ** 3, "lao -o writes AO")

# Cell scalars: each cell read as a voxel at its centre. The LAO of a
# volume's cell data equals, bit for bit and on the same geometry, the LAO
# of the same values as point data at the cells' centres; a note says so.
def write_image(path, values, dims, origin, cells):
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkIOXML import vtkXMLImageDataWriter
    image = vtkImageData()
    image.SetDimensions(*dims)
    image.SetOrigin(*origin)
    image.SetSpacing(1.0, 2.0, 0.5)
    array = numpy_to_vtk(values, deep=1)
    array.SetName("v")
    (image.GetCellData() if cells else image.GetPointData()).SetScalars(array)
    w = vtkXMLImageDataWriter()
    w.SetFileName(path)
    w.SetInputData(image)
    w.Write()


cell_values = (np.arange(20 * 18 * 16) * 2654435761 % 256).astype(np.uint8)
write_image(os.path.join(tmp, "cells.vti"), cell_values, (21, 19, 17), (0.0, 0.0, 0.0), True)
write_image(os.path.join(tmp, "centres.vti"), cell_values, (20, 18, 16), (0.5, 1.0, 0.25), False)
lao_of = {}
for name in ("cells", "centres"):
    rc, out, err = run("lao", os.path.join(tmp, name + ".vti"), "--threads", "1", "-o",
                       os.path.join(tmp, name + "-lao.vti"))
    reader = vtkXMLImageDataReader()
    reader.SetFileName(os.path.join(tmp, name + "-lao.vti"))
    reader.Update()
    image = reader.GetOutput()
    array = image.GetPointData().GetArray("AmbientOcclusion")
    lao_of[name] = (rc, err, image.GetDimensions(), image.GetOrigin(),
                    vtk_to_numpy(array) if array is not None else None)
(rc_c, err_c, dims_c, origin_c, ao_c), (rc_p, err_p, dims_p, origin_p, ao_p) = lao_of["cells"], lao_of["centres"]
check(rc_c == 0 and rc_p == 0 and ao_c is not None and ao_p is not None and dims_c == dims_p and
      np.allclose(origin_c, origin_p, rtol=0, atol=1e-12) and np.array_equal(ao_c, ao_p) and
      "holds cell scalars" in err_c and "holds cell scalars" not in err_p,
      f"lao of cell scalars equals lao at the cells' centres: rc={rc_c},{rc_p} dims {dims_c} "
      f"{dims_p} origin {origin_c} {origin_p} {err_c.strip()[:160]}")
check(ao_c is not None and float(np.ptp(ao_c)) > 0.1, "the cells' LAO is not constant (a blind comparison)")

# carve with a torus along the default path, verified, JSON summary.
carve_vti = os.path.join(tmp, "carve.vti")
rc, out, err = run("carve", os.path.join(data, "HeadMRVolume.mhd"), "--shape", "torus",
                   "--rays", "14", "--path", "20", "--verify", "--json", "-o", carve_vti)
check(rc == 0, f"carve torus --verify: rc={rc} {err.strip()[:300]}")
if rc == 0:
    summary = json.loads(out)
    run0 = summary["runs"][0]
    check(len(run0["poses"]) == 20, "20 poses reported")
    check(all(p["max_abs_difference"] == 0 for p in run0["poses"]), "verify exact at every pose")
    check(all(sum(p["counts"].values()) == summary["voxels"] for p in run0["poses"]),
          "category counts partition the volume")
    check(any(p["counts"]["affected"] > 0 for p in run0["poses"]), "the path affects voxels")
    check(all(k in run0["poses"][0]["ms"] for k in ("classify", "copy", "recompute", "cao_total"))
          and "speedup" in run0["poses"][0] and "full_lao_ms" in run0["poses"][0],
          "per-stage milliseconds, full LAO and speed-up in JSON")
    reader.SetFileName(carve_vti)
    reader.Update()
    pd = reader.GetOutput().GetPointData()
    check(all(pd.GetArray(n) is not None for n in ("AmbientOcclusion", "ClipCategory", "ClippedOpacity")),
          "carve -o writes AO, categories and clipped opacity")
    check(run0["summary"]["ao_format"] == "unorm16" and pd.GetArray("AmbientOcclusion") is not None
          and pd.GetArray("AmbientOcclusion").GetDataTypeAsString() == "unsigned short",
          "carve keeps and writes the AO as 16-bit by default (ao_format unorm16)")
    check(run0["poses"][0]["ms"]["setup"] > 0 and all(p["ms"]["setup"] == 0 for p in run0["poses"][1:])
          and run0["summary"]["setup_ms"] > 0,
          "the setup is reported at the first pose only, apart from the pose's own time")
rc, out, err = run("carve", os.path.join(data, "HeadMRVolume.mhd"), "--shape", "torus", "--rays", "6",
                   "--path", "3", "--verify", "--json", "--ao-format", "float", "-o", carve_vti)
if rc == 0:
    reader.Modified()
    reader.Update()
    check(json.loads(out)["runs"][0]["summary"]["ao_format"] == "float" and
          json.loads(out)["runs"][0]["summary"]["max_abs_difference"] == 0 and
          reader.GetOutput().GetPointData().GetArray("AmbientOcclusion").GetDataTypeAsString() == "float",
          "carve --ao-format float keeps a float AO, exact")
else:
    check(False, f"carve --ao-format float: rc={rc} {err.strip()[:300]}")

# Poses from a file and from the command line; meshes from .vtp and .stl.
poses = os.path.join(tmp, "poses.txt")
with open(poses, "w") as f:
    f.write("# tx ty tz rx ry rz scale\n33 33 33\n\n20 30 40 10 20 30 1.2\n40,25,30,0,90,0,0.8\n")
sphere = vtkSphereSource()
sphere.SetRadius(10)
sphere.Update()
vtp = os.path.join(tmp, "sphere.vtp")
wv = vtkXMLPolyDataWriter()
wv.SetInputData(sphere.GetOutput())
wv.SetFileName(vtp)
wv.Write()
stl = os.path.join(tmp, "sphere.stl")
ws = vtkSTLWriter()
ws.SetInputData(sphere.GetOutput())
ws.SetFileName(stl)
ws.Write()
for mesh in (vtp, stl):
    rc, out, err = run("carve", os.path.join(data, "neghip.slc"), "--mesh", mesh, "--poses", poses,
                       "--rays", "6", "--verify", "--json")
    check(rc == 0 and len(json.loads(out)["runs"][0]["poses"]) == 3,
          f"carve --mesh {os.path.basename(mesh)} --poses: rc={rc} {err.strip()[:200]}")
rc, out, err = run("carve", os.path.join(data, "neghip.slc"), "--shape", "cube", "--pose", "30 30 30 45 0 0",
                   "--pose", "10,10,10", "--rays", "6,26", "--mode", "probe", "--verify")
check(rc == 0 and "| 6 |" in out and "| 26 |" in out, f"carve --pose, two ray sets, probe: rc={rc}")
# ParaView's panel names the modes Subtraction and Probing: those names are
# taken too, as the same runs (a trial's --mode probing was refused).
rc2, out2, err2 = run("carve", os.path.join(data, "neghip.slc"), "--shape", "cube", "--pose", "30 30 30 45 0 0",
                      "--rays", "6", "--mode", "Probing", "--json")
rc3, out3, err3 = run("carve", os.path.join(data, "neghip.slc"), "--shape", "cube", "--pose", "30 30 30 45 0 0",
                      "--rays", "6", "--mode", "probe", "--json")
counts = lambda text: [p["counts"] for p in json.loads(text)["runs"][0]["poses"]] if text.strip() else None
check(rc2 == 0 and rc3 == 0 and json.loads(out2)["mode"] == "probe" and counts(out2) == counts(out3),
      f"carve --mode Probing is --mode probe: rc={rc2} {err2.strip()[:200]}")

# Errors: clear message, non-zero exit, no crash.
garbage = os.path.join(tmp, "garbage.slc")
with open(garbage, "wb") as f:
    f.write(b"\x00\x01not a volume at all" * 10)
open_mesh = os.path.join(tmp, "open.vtp")
cut = vtkPolyData()
cut.DeepCopy(sphere.GetOutput())
cut.DeleteCell(3)
cut.RemoveDeletedCells()
wv.SetInputData(cut)
wv.SetFileName(open_mesh)
wv.Write()
neghip = os.path.join(data, "neghip.slc")
expect_error(["lao", os.path.join(tmp, "missing.vti")], 2, "cannot open", "missing file")
# An empty file and a directory: our words, not VTK's XML parser's.
empty_vti = os.path.join(tmp, "empty.vti")
open(empty_vti, "w").close()
os.makedirs(os.path.join(tmp, "folder.vti"), exist_ok=True)
empty_vtp = os.path.join(tmp, "empty.vtp")
wv.SetInputData(vtkPolyData())
wv.SetFileName(empty_vtp)
wv.Write()
for args, words, what in ((["lao", empty_vti], "empty (0 bytes)", "an empty .vti"),
                          (["lao", os.path.join(tmp, "folder.vti")], "is a directory", "a directory"),
                          (["carve", neghip, "--mesh", empty_vti.replace(".vti", ".stl")], "no such file",
                           "a missing mesh"),
                          # A mesh with no points, as VTK writes one: its
                          # reader's "No Points element" is not the user's.
                          (["carve", neghip, "--mesh", empty_vtp], "holds no points", "an empty .vtp mesh"),
                          (["surface", empty_vtp, "-o", os.path.join(tmp, "e.png")], "holds no points",
                           "an empty .vtp surface"),
                          # A missing mesh and no -o: the missing file first
                          # (it asked for -o, then, given one, for the file).
                          (["surface", os.path.join(tmp, "none.vtp")], "no such file",
                           "a missing surface mesh without -o"),
                          # -o naming a folder: refused before the work (it
                          # printed the run's JSON, then failed to write).
                          (["lao", neghip, "--json", "-o", os.path.join(tmp, "folder.vti")], "it is a folder",
                           "-o naming a folder")):
    rc, out, err = run(*args)
    check(rc == 2 and words in err and "ERR|" not in err and "XML" not in err,
          f"{what}: one clear line, no VTK output: rc={rc} {err.strip()[:200]!r}")
expect_error(["lao", garbage], 2, "cannot read", "unreadable volume")
expect_error(["lao", os.path.join(tmp, "poses.txt")], 2, "unknown volume format", "unknown format")
expect_error(["lao", neghip, "--rays", "7"], 2, "bad ray pattern", "bad ray pattern")
expect_error(["lao", neghip, "--bogus"], 2, "unknown option", "unknown option")
expect_error(["lao", neghip, "--reach", "-3"], 2, "a positive length", "negative reach")
expect_error(["frobnicate", neghip], 2, "unknown command", "unknown command")
rc, out, err = run("bench", "frobnicate")
check(rc == 2 and err.strip().splitlines()[-1:] and err.strip().splitlines()[-1].startswith(
    "cao: error: unknown benchmark"), f"an unknown benchmark, in the tool's words: rc={rc} {err.strip()[:160]!r}")
expect_error(["carve", neghip, "--pose", "1 2"], 2, "a pose is", "malformed pose")
expect_error(["carve", neghip, "--mesh", open_mesh], 2, "open", "open clip mesh")
expect_error(["carve", neghip, "--ao-format", "half"], 2, "--ao-format: bad value 'half' (expected unorm16",
             "an unknown AO format")
expect_error(["carve", neghip, "--shape", "teapot"], 2, "--shape: bad value 'teapot' (expected sphere",
             "unknown shape")
expect_error(["carve", neghip, "--poses", os.path.join(tmp, "nope.txt")], 2, "cannot open", "missing pose file")
# Maps too fine to make: the error names the option that sets their pixel
# size (it named the filter's property PixelSize, which cao has not).
expect_error(["carve", neghip, "--pixel-size", "0.001", "--path", "2"], 2, "set a larger --pixel-size",
             "maps too fine name --pixel-size")
rc, out, err = run("--help")
check(rc == 0 and all(re.search(r"^  %s " % c, out, re.M) for c in ("lao", "carve", "tf", "render", "surface", "bench")),
      "--help lists the commands")
rc, out, err = run("--help-all")
check(rc == 0 and all(o in out for o in ("--quality", "--density", "--offset", "--variation", "--image")),
      "--help-all lists every command's options (--quality, --density, --offset, --variation, --image)")
# Options that conflict or repeat are refused, naming both.
expect_error(["carve", neghip, "--shape", "cube", "--mesh", open_mesh], 2, "--shape excludes --mesh",
             "--shape and --mesh together")
expect_error(["lao", neghip, "--reach", "2", "--reach", "3"], 2, "--reach is given more than once",
             "a repeated option")
# A flag too (CLI11 took its last occurrence without a word).
expect_error(["lao", neghip, "--json", "--json"], 2, "--json is given more than once", "a repeated flag")
expect_error(["render", neghip, "--no-clip", "--no-clip", "-o", os.path.join(tmp, "f_%d.png")], 2,
             "--no-clip is given more than once", "a repeated flag callback")
# What the new user's trial found: each refused in one line, before any work.
for args, words, what in (
        (["lao", neghip, "--samples", "0x10"], "--samples: bad value '0x10'", "a hexadecimal integer"),
        (["lao", neghip, "--reach", " 5"], "--reach: bad value ' 5'", "a leading blank"),
        (["lao", neghip, "-o", os.path.join(tmp, "ao.png")], "(a .vti file)", "lao -o that is not .vti"),
        (["lao", neghip, "-o", os.path.join(tmp, "none", "ao.vti")], "does not exist", "lao -o into no folder"),
        (["lao", neghip, "--density", "1", "--samples", "4"], "give one", "--density with --samples"),
        (["carve", neghip, "--pose", "30 30 30", "--path", "5"], "--pose excludes --path", "--pose with --path"),
        (["carve", neghip, "--pose", "16 16"], "--pose: ", "a short pose names --pose"),
        (["carve", neghip, "--size", "1e100"], "--size: bad value '1e100'", "a clip size beyond float"),
        (["render", neghip, "--size", "1e100", "-o", os.path.join(tmp, "s_%d.png")], "--size: bad value",
         "render: a clip size beyond float (exit 1 before)"),
        (["render", neghip, "--no-clip", "--aa", "3"], "--no-clip", "render --no-clip with --aa"),
        (["render", neghip, "--no-ao", "--ao-strength", "0.5"], "--no-ao", "render --no-ao with --ao-strength"),
        (["bench", "surface-scale", os.path.join(data, "Bunny.vtp"), "-o", os.path.join(tmp, "none", "x")],
         "does not exist", "bench surface-scale -o into no folder"),
        # --pose takes one value: what follows it is the volume or an extra
        # argument, never a second pose (it was read as one, and the volume
        # was then "missing").
        (["carve", "--pose", "1 0 0", neghip, "--path", "3"], "--pose excludes --path",
         "--pose before the volume leaves the volume in place"),
        (["carve", neghip, "--pose", "1 0 0", "stray"], "unexpected argument 'stray'",
         "a stray argument after --pose is not a pose"),
        # Sizes are whole decimal numbers in range: 4294967312 wrapped to 16.
        (["render", neghip, "--image", "4294967312x16"], "--image: bad value '4294967312x16'",
         "an --image side past 32 bits"),
        (["render", neghip, "--image", "16x-16"], "--image: bad value '16x-16'", "a negative --image side"),
        (["render", neghip, "--image", "+64x64"], "--image: bad value '+64x64'", "a signed --image side"),
        (["bench", "surface-frame", os.path.join(data, "Bunny.vtp"), "--sizes", "64x64,4294967312x16"],
         "4294967312x16", "a --sizes item past 32 bits"),
        (["lao", neghip, "--json=maybe"], "--json is a flag: it takes no value", "a value given to a flag"),
        (["lao", "--bogus"], "unknown option '--bogus'", "an unknown option before the missing volume"),
        # A list item given twice ran twice.
        (["carve", neghip, "--rays", "6,14,6"], "'6' is given twice", "a ray pattern given twice"),
        (["bench", "surface-frame", os.path.join(data, "Bunny.vtp"), "--sizes", "64x64,64x64"],
         "'64x64' is given twice", "an image size given twice")):
    rc, out, err = run(*args)
    lines = [l for l in err.splitlines() if l.strip()]
    check(rc == 2 and len(lines) == 1 and words in err, f"{what}: rc={rc} {err.strip()[:200]!r}")
rc, out, err = run("surface", os.path.join(data, "Bunny.vtp"), "--slices", "64.0",
                   "-o", os.path.join(tmp, "slices.png"))
check(rc == 0, f"surface --slices 64.0 is 64, as --samples 1e1 is 10: rc={rc} {err.strip()[:200]!r}")
# Voxel cones at a radius under a voxel of the grid read the surface they
# start from (a trial saw black speckle, mean AO 0.86 where the reference
# gives 1.000): no AO, and a warning; at the default radius neither.
for radius, silent in (("0.00001", False), (None, True)):
    extra = ["--radius", radius] if radius else []
    rc, out, err = run("surface", os.path.join(data, "Bunny.vtp"), "--image", "120x90", "--ao-only", "--json",
                       *extra, "-o", os.path.join(tmp, "vct_radius.png"))
    mean = json.loads(out)["mean_ao"] if rc == 0 else None
    said = "is under a voxel of the grid" in err
    check(rc == 0 and said != silent and (mean < 1.0 if silent else mean == 1.0),
          f"vct radius {radius}: mean AO {mean}, warned {said}: rc={rc} {err.strip()[:200]!r}")
# --radius 0 is the default, as the view's Surface AO Radius 0 is (a trial
# saw the CLI refuse the value the view takes); a negative one is refused.
radii = []
for extra in (["--radius", "0"], []):
    rc, out, err = run("surface", os.path.join(data, "Bunny.vtp"), "--image", "80x60", "--json", *extra,
                       "-o", os.path.join(tmp, "radius_default.png"))
    radii.append(json.loads(out)["radius"] if rc == 0 else None)
rc, out, err = run("surface", os.path.join(data, "Bunny.vtp"), "--radius", "-1", "-o",
                   os.path.join(tmp, "radius_negative.png"))
check(radii[0] is not None and radii[0] == radii[1] and radii[0] > 0 and rc == 2 and
      "or 0 for the default" in err,
      f"surface --radius 0 is the default radius ({radii}); -1 refused: rc={rc} {err.strip()[:200]!r}")
rc, out, err = run("carve", neghip, "--pose", "30 30 30", "--pose", "20 20 20", "--rays", "6", "--json")
check(rc == 0 and len(json.loads(out)["runs"][0]["poses"]) == 2,
      f"--pose twice gives two poses: rc={rc} {err.strip()[:200]!r}")
# Help wins over any other mistake on the line, and `cao help COMMAND` and
# `cao version` are the same as --help and --version.
for args, words, what in (
        (["carve", "--size", "abc", "--help"], "Usage: cao carve", "--help after a bad value"),
        (["render", neghip, "--image", "0x0", "-h"], "Usage: cao render", "-h after a bad --image"),
        (["bench", "surface", "--help"], "Usage: cao bench surface", "a benchmark's --help"),
        (["help", "bench", "accuracy"], "Usage: cao bench accuracy", "cao help bench accuracy"),
        (["help"], "Usage: cao [OPTIONS] SUBCOMMAND", "cao help")):
    rc, out, err = run(*args)
    check(rc == 0 and words in out and not err, f"{what}: rc={rc} {out[:80]!r} {err.strip()[:200]!r}")
rc, out, err = run("version")
check(rc == 0 and out.startswith("cao (ContextualAO) "), f"cao version: rc={rc} {out.strip()[:100]}")
rc, out, err = run("lao", neghip, "--samples", "1e1", "--rays", "6", "--json")
check(rc == 0 and json.loads(out)["samples"] == 10, f"--samples 1e1 is 10 (CLI11 refused it): rc={rc} {err.strip()[:200]}")
expect_error(["lao"], 2, "missing VOLUME", "no volume")
expect_error(["bench"], 2, "missing benchmark (expected accuracy", "no benchmark")
expect_error([], 2, "missing command (expected lao, carve", "no command")
rc, out, err = run("--version")
check(rc == 0 and out.startswith("cao (ContextualAO) ") and "VTK 9." in out and not err,
      f"--version: rc={rc} {out.strip()[:100]}")
expect_error(["--versions"], 2, "unknown option '--versions'", "--versions is not --version")

# Quality levels: `--quality low` runs, reports (JSON) and records
# (LAOSettings in the .vti) the settings in effect, and its AO equals the
# AO of those settings given as explicit options.
def lao_field(path):
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    a = image.GetFieldData().GetArray("LAOSettings")
    params = {a.GetComponentName(c): a.GetComponent(0, c) for c in range(a.GetNumberOfComponents())}
    return params, vtk_to_numpy(image.GetPointData().GetArray("AmbientOcclusion")).copy()


level_vti = os.path.join(tmp, "low.vti")
rc, out, err = run("lao", neghip, "--quality", "low", "--reach", "4", "--json", "-o", level_vti)
check(rc == 0, f"lao --quality low: rc={rc} {err.strip()[:200]}")
if rc == 0:
    q = json.loads(out)
    params, level_ao = lao_field(level_vti)
    check(q["quality"] == "low" and params["Quality"] == 1 and
          all(k in q for k in ("pattern", "samples", "start_offset", "variation")),
          f"--quality low: the JSON and the field data name the level: {q}")
    pattern = q["pattern"]
    check(params["RayPattern"] == {"6": 0, "14": 1, "26": 2, "54": 3}.get(pattern, 4) and
          (not pattern.startswith("fib:") or params["NumberOfRays"] == int(pattern[4:])) and
          params["NumberOfSamples"] == q["samples"] and params["StartOffset"] == q["start_offset"],
          f"--quality low: the field data holds the pattern in effect ({pattern}): {params}")
    hand_vti = os.path.join(tmp, "by-hand.vti")
    rc, out, err = run("lao", neghip, "--rays", pattern, "--samples", str(q["samples"]),
                       "--offset", repr(q["start_offset"]), "--variation", q["variation"],
                       "--reach", "4", "--json", "-o", hand_vti)
    check(rc == 0, f"lao with the level's settings by hand: rc={rc} {err.strip()[:200]}")
    if rc == 0:
        h = json.loads(out)
        hand_params, hand_ao = lao_field(hand_vti)
        check(h["quality"] == "custom" and hand_params["Quality"] == 0 and
              all(h[k] == q[k] for k in ("pattern", "rays", "samples", "start_offset", "variation")),
              "the explicit options give the level's settings")
        check(np.array_equal(level_ao, hand_ao),
              "--quality low equals its settings given by hand, voxel for voxel")
    rc, out, err = run("lao", neghip, "--reach", "4", "-o", os.path.join(tmp, "default.vti"))
    check(rc == 0 and np.array_equal(level_ao, lao_field(os.path.join(tmp, "default.vti"))[1])
          and lao_field(os.path.join(tmp, "default.vti"))[0]["Quality"] == 1,
          "the default is --quality low, voxel for voxel")
    rc, out, err = run("lao", neghip, "--reach", "4", "--rays", "26", "--density", "1",
                       "--variation", "none", "-o", os.path.join(tmp, "old-default.vti"))
    old_params, old_ao = lao_field(os.path.join(tmp, "old-default.vti")) if rc == 0 else ({}, None)
    check(rc == 0 and old_params.get("Quality") == 0 and old_params.get("RayPattern") == 2
          and not np.array_equal(level_ao, old_ao),
          "--rays 26 --density 1 --variation none without --quality: custom, the old default, "
          "another AO")
    rc, out, err = run("lao", neghip, "--reach", "4", "--quality", "medium", "--rays", "26",
                       "-o", os.path.join(tmp, "conflict.vti"))
    check(rc == 2 and "cannot be combined with --rays" in err,
          f"--quality with --rays is refused: rc={rc} {err.strip()[:160]}")
# carve with a quality level: the contextual AO is still exact.
rc, out, err = run("carve", neghip, "--quality", "medium", "--reach", "4", "--path", "3",
                   "--verify", "--json")
check(rc == 0 and json.loads(out)["runs"][0]["quality"] == "medium" and
      all(p["max_abs_difference"] == 0 for p in json.loads(out)["runs"][0]["poses"]),
      f"carve --quality medium --verify: rc={rc} {err.strip()[:200]}")
# The LAO's former level names are refused, naming the new one (one
# quality vocabulary for every technique).
for old, new in (("interactive", "low"), ("balanced", "medium"), ("reference", "high")):
    expect_error(["lao", neghip, "--quality", old], 2, "'%s' is now '%s'" % (old, new), "--quality " + old)
expect_error(["lao", neghip, "--quality", "best"], 2, "expected low, medium, high or custom", "--quality best")
expect_error(["lao", neghip, "--quality", "Low"], 2, "the names are lower case: 'low'", "--quality Low")
# Explicit offset, density and variation are accepted and recorded.
rc, out, err = run("lao", neghip, "--reach", "4", "--rays", "6", "--density", "2", "--offset", "0.5",
                   "--variation", "rotate+jitter", "--json")
check(rc == 0 and json.loads(out)["samples"] == 8 and json.loads(out)["start_offset"] == 0.5 and
      json.loads(out)["variation"] == "rotate+jitter",
      f"lao --density 2 --offset 0.5 --variation rotate+jitter: rc={rc} {out.strip()[:300]}")
expect_error(["lao", neghip, "--quality", "bogus"], 2, "--quality: bad value 'bogus' (expected low",
             "unknown quality")
expect_error(["carve", neghip, "--variation", "bogus"], 2, "--variation: bad value 'bogus' (expected none",
             "unknown variation")
expect_error(["lao", neghip, "--offset", "1.5"], 2, "--offset", "offset out of range")
expect_error(["lao", neghip, "--density", "0"], 2, "--density", "zero density")
expect_error(["lao", neghip, "--quality", "high", "--rays", "6"], 2, "cannot be combined",
             "a quality level and an explicit ray pattern")
expect_error(["render", neghip, "--quality", "bogus", "-o", os.path.join(tmp, "x_%d.png")], 2,
             "--quality: bad value 'bogus'", "render: unknown quality")
expect_error(["render", neghip, "--variation", "spin", "-o", os.path.join(tmp, "x_%d.png")], 2,
             "--variation: bad value 'spin'", "render: unknown variation")
expect_error(["render", neghip, "--offset", "1.5", "-o", os.path.join(tmp, "x_%d.png")], 2,
             "--offset", "render: offset out of range")

# render: PNG frames of a moving clip sphere with the contextual-AO mapper
# (EGL window, no X), each frame's work report as JSON.
frames = os.path.join(tmp, "frame_%02d.png")
rc, out, err = run("render", neghip, "--image", "96x80", "--path", "3", "--window", "egl",
                   "--rays", "6", "--json", "-o", frames)
if rc == 125 or "no EGL" in err:
    # Only where OpenGL is not required (CAO_REQUIRE_GL, set by .ci/run).
    check(os.environ.get("CAO_REQUIRE_GL", "0") in ("", "0"),
          "render ran (CAO_REQUIRE_GL is set): rc=%d %s" % (rc, err.strip()[:200]))
    print("render: skipped, no EGL context:", err.strip())
else:
    check(rc == 0, "render exits 0: " + err)
    reports = json.loads(out) if rc == 0 else []
    check(len(reports) == 3, "render: one report per frame")
    for i, r in enumerate(reports):
        png = frames % i
        check(os.path.exists(png) and open(png, "rb").read(8) == b"\x89PNG\r\n\x1a\n",
              "render: frame %d is a PNG" % i)
        names = [s["name"] for s in r["report"]["stages"]]
        check("raycast" in names, "render: frame %d ray cast" % i)
        check(r.get("pose") == i and r.get("file") == png,
              "render --json: entry %d names its pose and file (%s, %s)" % (i, r.get("pose"), r.get("file")))
    if len(reports) == 3:
        first = [s["name"] for s in reports[0]["report"]["stages"]]
        check("precompute" in first and "depth_maps" in first, "render: frame 0 precomputes")
        later = [s["name"] for s in reports[1]["report"]["stages"]]
        check("precompute" not in later and "depth_maps" not in later and "classify" in later,
              "render: a pose change only re-classifies and recomputes: %s" % later)
    # A ParaView preset file, and the built-in ones by name.
    preset = os.path.join(tmp, "preset.json")
    with open(preset, "w") as f:
        json.dump([{"Name": "mine", "ColorSpace": "RGB",
                    "RGBPoints": [0, 0, 0, 1, 255, 1, 1, 0],
                    "Points": [0, 0, 0.5, 0, 60, 0, 0.5, 0, 255, 0.9, 0.5, 0]}], f)
    rc, out, err = run("render", neghip, "--image", "64x64", "--no-clip", "--window", "egl",
                       "--rays", "6", "--preset-file", preset, "--preset", "mine", "-o",
                       os.path.join(tmp, "p_%d.png"))
    check(rc == 0 and os.path.exists(os.path.join(tmp, "p_0.png")), "render with a ParaView preset: " + err)
    # %% is a literal percent sign and the width pads with zeros.
    rc, out, err = run("render", neghip, "--image", "64x64", "--no-clip", "--window", "egl",
                       "--rays", "6", "-o", os.path.join(tmp, "pct%%_%04i.png"))
    check(rc == 0 and os.path.exists(os.path.join(tmp, "pct%_0000.png")),
          "render -o with %%%% and %%04i: " + err)
    # A quality level (not a colour preset) for the mapper's LAO.
    rc, out, err = run("render", neghip, "--image", "64x64", "--no-clip", "--window", "egl",
                       "--quality", "low", "--reach", "4", "--json", "-o",
                       os.path.join(tmp, "q_%d.png"))
    check(rc == 0 and "precompute" in [s["name"] for s in json.loads(out)[0]["report"]["stages"]],
          "render --quality low: " + err)
    # The AO it draws is stated: the level and what it stands for.
    said = json.loads(out)[0].get("ao", "") if rc == 0 else ""
    check(said.startswith("LAO quality low: 14 rays") and "reach 4 voxels" in said,
          "render --json states the LAO settings: %r" % said)
    rc, out, err = run("render", neghip, "--image", "32x32", "--no-clip", "--window", "egl",
                       "--quality", "medium", "-o", os.path.join(tmp, "m.png"))
    check(rc == 0 and "AO: LAO quality medium: 14 rays, 4 sample(s) per voxel, reach 8 voxels" in out,
          "render states the LAO settings in its header: %r" % out[:300])
    # A frame of background alone says so (a plane whose first pose of the
    # path leaves only a transparent slab); frames with matter do not.
    rc, out, err = run("render", neghip, "--image", "48x48", "--shape", "plane", "--path", "4",
                       "--window", "egl", "--rays", "6", "-o", os.path.join(tmp, "plane_%d.png"))
    notes = [i for i, line in enumerate(out.splitlines()) if "only the background" in line]
    check(rc == 0 and out.splitlines()[notes[0] - 1].lstrip().startswith("frame   0") if notes else False,
          "render: a background-only frame (plane, pose 0) is noted: %s" % out.strip()[:400])
    check(len(notes) == 1, "render: only that frame is noted (%d notes)" % len(notes))
    rc, out, err = run("render", neghip, "--image", "48x48", "--shape", "plane", "--path", "4",
                       "--window", "egl", "--rays", "6", "--json", "-o", os.path.join(tmp, "plane_%d.png"))
    flags = [r.get("background_only") for r in json.loads(out)] if rc == 0 else []
    check(flags == [True, False, False, False], "render --json: background_only per frame: %s" % flags)
    # A frame whose clip removes no whole voxel says so (the path's two end
    # poses lie outside the volume); frames that carve do not.
    rc, out, err = run("render", neghip, "--image", "48x48", "--path", "2", "--window", "egl", "--rays", "6",
                       "-o", os.path.join(tmp, "miss_%d.png"))
    check(rc == 0 and out.count("the clip removes no whole voxel") == 2,
          "render --path 2: both frames noted: %r" % out.strip()[-400:])
    rc, out, err = run("render", neghip, "--image", "48x48", "--path", "4", "--window", "egl", "--rays", "6",
                       "-o", os.path.join(tmp, "hit_%d.png"))
    check(rc == 0 and out.count("the clip removes no whole voxel") == 2,
          "render --path 4: the two end frames noted, the middle ones not: %r" % out.strip()[-600:])
    # With --no-clip the note names the opacity and the camera, not the clip
    # (it said "the clip leaves nothing visible").
    rc, out, err = run("render", neghip, "--image", "48x48", "--no-clip", "--window", "egl", "--rays", "6",
                       "--unit-distance", "1e9", "-o", os.path.join(tmp, "clear_%d.png"))
    said = [line for line in out.splitlines() if "only the background" in line]
    check(rc == 0 and len(said) == 1 and "the opacity map" in said[0] and "clip" not in said[0],
          "render --no-clip of a transparent volume: the note leaves the clip out: %r" % said)
expect_error(["render", neghip, "--preset", "nope", "-o", os.path.join(tmp, "x_%d.png")], 2,
             "no preset named", "unknown preset")
expect_error(["render", neghip, "--preset-file", os.path.join(tmp, "none.json"), "-o",
              os.path.join(tmp, "x_%d.png")], 2, "cannot read the preset", "missing preset file")
# A file's preset taken without --preset: its errors name it (they said
# "preset ''"); the control: the same error with --preset gives its name too.
bad_preset = os.path.join(tmp, "bad_preset.json")
with open(bad_preset, "w") as f:
    json.dump([{"Name": "Bad", "RGBPoints": [0, 0, 0]}], f)
expect_error(["render", neghip, "--preset-file", bad_preset, "-o", os.path.join(tmp, "x_%d.png")], 2,
             "preset 'Bad': \"RGBPoints\" must be a list of 4-tuples", "a bad preset named without --preset")
expect_error(["render", neghip, "--preset-file", bad_preset, "--preset", "Bad", "-o", os.path.join(tmp, "x_%d.png")],
             2, "preset 'Bad'", "a bad preset named by --preset")
expect_error(["render", neghip, "-o", os.path.join(tmp, "x.png")], 2, "frame-number conversion",
             "output without a frame pattern")
# Bad input to render is exit 2, said before its first line of output
# (an open clip mesh, a NaN mesh point, two components, NaN scalars, a
# negative spacing with --no-ao gave exit 1 after the header, and the
# mapper's "drawn unclipped"); the control: the same volume and a closed
# shape render.
from vtkmodules.vtkFiltersSources import vtkCylinderSource, vtkSphereSource as _Sphere
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter as _PW, vtkXMLImageDataWriter as _IW
from vtkmodules.vtkCommonDataModel import vtkImageData as _Img
open_cyl = os.path.join(tmp, "open_cyl.vtp")
cyl = vtkCylinderSource()
cyl.CappingOff()
cyl.SetRadius(10)
cyl.SetHeight(20)
pw = _PW()
pw.SetInputConnection(cyl.GetOutputPort())
pw.SetFileName(open_cyl)
pw.Write()
def small_volume(name, components=1, spacing=(1, 1, 1), nan=False, inf=False, all_nan=False):
    img = _Img()
    img.SetDimensions(12, 12, 12)
    img.SetSpacing(*spacing)
    img.AllocateScalars(10, components)
    arr = img.GetPointData().GetScalars()
    for c in range(components):
        arr.FillComponent(c, 100.0)
    arr.SetComponent(0, 0, 0.0)
    if nan:
        arr.SetComponent(5, 0, float("nan"))
    if inf:
        arr.SetComponent(5, 0, float("inf"))
    if all_nan:
        arr.FillComponent(0, float("nan"))
    path = os.path.join(tmp, name)
    iw = _IW()
    iw.SetInputData(img)
    iw.SetFileName(path)
    iw.Write()
    return path
good_vol = small_volume("good.vti")
for args, words, what in (
        ([good_vol, "--mesh", open_cyl], "the clip mesh is open", "render with an open clip mesh"),
        ([small_volume("two.vti", components=2), "--no-clip"], "has 2 components a voxel", "render of 2 components"),
        ([small_volume("inf.vti", inf=True), "--no-clip"], "1 infinite value(s)", "render of an infinite voxel"),
        ([small_volume("allnan.vti", all_nan=True), "--no-clip"], "is NaN: nothing to draw", "render of all NaN"),
        ([small_volume("neg.vti", spacing=(-1, 1, 1)), "--no-clip", "--no-ao"], "must be positive and finite",
         "render of a negative spacing, AO off")):
    rc, out, err = run("render", *args, "--image", "32x32", "-o", os.path.join(tmp, "bad_%d.png"))
    check(rc == 2 and words in err and out == "" and not os.path.exists(os.path.join(tmp, "bad_0.png")),
          "%s: exit 2, said before any output (rc %d, stdout %r, stderr %r)" % (what, rc, out[:80], err.strip()[:160]))
# A volume 1e60 world units across: the default clip shape would have
# infinite float32 points; refused naming the size and the limit (it blamed
# "the clip mesh" for a NaN or infinite coordinate); at 1e30 it carves.
huge = small_volume("huge.vti", spacing=(1e60, 1e60, 1e60))
for command in ("render", "carve"):
    expect_error([command, huge, "--path", "1", "--rays", "6"] + (["-o", os.path.join(tmp, "huge_%d.png")] if command == "render" else []),
                 2, "beyond the float32 coordinates", f"{command} of a volume at spacing 1e60")
rc, out, err = run("carve", small_volume("big.vti", spacing=(1e30, 1e30, 1e30)), "--path", "1", "--rays", "6")
check(rc == 0, f"the control: carve at spacing 1e30 (rc {rc}, {err.strip()[:160]!r})")
# A clip that removes no whole voxel is said: carve's default shape on
# voxels 7 units long (a quarter of the smallest extent, 3.5) at every pose
# (it printed nothing); the control, neghip's default path, carves.
aniso = small_volume("aniso.vti", spacing=(0.3, 2.5, 7.0))
rc, out, err = run("carve", aniso, "--path", "4", "--rays", "6")
check(rc == 0 and "removes no whole voxel at any pose" in err,
      f"carve whose clip removes no whole voxel says so: rc={rc} {err.strip()[-300:]!r}")
rc, out, err = run("carve", neghip, "--path", "4", "--rays", "6")
check(rc == 0 and "removes no whole voxel" not in err, f"the control: neghip's path carves without the note: {err.strip()[-200:]!r}")
# A pose scale of 1e200 in carve names the scale's limits (it said "must be
# an invertible transform").
expect_error(["carve", good_vol, "--pose", "4 4 4 0 0 0 1e200", "--rays", "6"], 2,
             "the scale must lie in", "carve with a pose scale of 1e200")
# A NaN voxel draws as empty space, as the LAO takes it, said once (it was
# refused: no frame).
rc, out, err = run("render", small_volume("nan.vti", nan=True), "--no-clip", "--image", "32x32", "-o",
                   os.path.join(tmp, "nan_%d.png"))
check(rc == 0 and os.path.exists(os.path.join(tmp, "nan_0.png")) and
      err.count("1 NaN value(s): drawn as empty space") == 1,
      "render of a NaN voxel: drawn, one warning (rc %d, %r)" % (rc, err.strip()[:200]))
# NaN voxels spread through the volume (every other one) blank every cell:
# the background-only note names them (it blamed the opacity map or the
# camera only).
spread = _Img()
spread.SetDimensions(12, 12, 12)
spread.AllocateScalars(10, 1)
spread_a = vtk_to_numpy(spread.GetPointData().GetScalars())
spread_a[:] = 100.0
spread_a[::2] = np.nan
spread_path = os.path.join(tmp, "spread_nan.vti")
iw = _IW()
iw.SetInputData(spread)
iw.SetFileName(spread_path)
iw.Write()
rc, out, err = run("render", spread_path, "--no-clip", "--image", "32x32", "-o", os.path.join(tmp, "spread_%d.png"))
said = [line for line in out.splitlines() if "only the background" in line]
check(rc == 0 and len(said) == 1 and "NaN value(s) blank every cell with a NaN corner" in said[0],
      "render of spread NaN voxels: the note names them (rc %d, %r)" % (rc, said))
# The control: a volume without NaN, transparent at the default preset,
# gets the note without them.
rc, out, err = run("render", good_vol, "--no-clip", "--image", "32x32", "-o", os.path.join(tmp, "clear_good_%d.png"))
said = [line for line in out.splitlines() if "only the background" in line]
check(rc == 0 and len(said) == 1 and "NaN" not in said[0] and "the opacity map" in said[0],
      "the control: no NaN, the note names the opacity map alone (rc %d, %r)" % (rc, said))
rc, out, err = run("render", good_vol, "--shape", "sphere", "--path", "1", "--image", "32x32", "-o",
                   os.path.join(tmp, "good_%d.png"))
check(rc == 0 and os.path.exists(os.path.join(tmp, "good_0.png")),
      "the control: the same volume with a closed clip shape renders (rc %d, %r)" % (rc, err.strip()[:160]))
# -o is a frame pattern, never a printf format: conversions other than one
# %d or %i are refused (before, %s%n crashed and %s wrote "(null)").
for pattern in ("x_%s%s%s%s%n.png", "x_%s.png", "x_%d_%d.png", "x_%-3d.png", "x_%10d.png"):
    expect_error(["render", neghip, "-o", os.path.join(tmp, pattern)], 2,
                 "frame-number conversion", "-o %r refused" % pattern)
expect_error(["render", neghip, "--image", "5x5"], 2, "--image", "tiny image")
# One frame may take a plain name (it needed a %d); more frames may not.
rc, out, err = run("render", neghip, "--no-clip", "--image", "32x32", "-o", os.path.join(tmp, "one.png"))
check(rc == 0 and os.path.exists(os.path.join(tmp, "one.png")),
      "render of one frame to a plain name: rc=%d %r" % (rc, err.strip()[:200]))
rc, out, err = run("render", neghip, "--path", "3", "--image", "32x32", "-o", os.path.join(tmp, "three.png"))
check(rc == 2 and "names one file, but 3 frames are drawn" in err and out == "" and
      not os.path.exists(os.path.join(tmp, "three.png")),
      "render of 3 frames to a plain name is refused before any output: rc=%d %r" % (rc, err.strip()[:200]))

# Held-out defects (issue 13), each with the case that found it.
head = os.path.join(data, "HeadMRVolume.mhd")
bunny = os.path.join(data, "Bunny.vtp")

# The same torus in the world, its size in the mesh or in the pose scale:
# the same clipped and affected voxels, and the clip right against the exact
# torus (--verify-geometry) as well as equal to a full recompute (--verify).
counts = []
for size, scale in (("1", "30"), ("30", "1"), ("0.03", "1000")):
    rc, out, err = run("carve", head, "--shape", "torus", "--size", size, "--pose",
                       "73.4 176.6 34.1 -101.1 -1.4 -103.7 " + scale, "--rays", "6", "--verify",
                       "--verify-geometry", "--json")
    check(rc == 0, f"carve torus size {size} scale {scale} --verify --verify-geometry: rc={rc} "
                   f"{err.strip()[:300]}")
    if rc == 0:
        pose = json.loads(out)["runs"][0]["poses"][0]
        g = pose["geometry"]
        check(g["wrong_inside"] == 0 and g["wrong_outside"] == 0 and g["must_be_inside"] > 0 and
              abs(g["map_pixel"] - 2.0) < 1e-6,
              f"size {size} scale {scale}: geometry {g}")
        counts.append((pose["counts"]["clipped"], pose["counts"]["affected"]))
check(len(counts) == 3 and len(set(counts)) == 1,
      f"the clipped and affected sets do not depend on the size/scale split: {counts}")
# A plane (the half-space z >= 0 of the pose, issue 15): exact against a
# full recompute and against the exact half-space at several orientations;
# the same world plane at scale 1 and at scale 10 (and 0.01) clips the same
# voxels; turned by 90 degrees it clips others (the negative control: the
# counts see the plane's orientation).
plane_counts = {}
for label, pose in (("a", "94 120 82 0 0 0 1"), ("b", "94 120 82 0 0 0 10"), ("e", "94 120 82 0 0 0 0.01"),
                    ("c", "94 120 82 30 20 10 1"), ("d", "94 120 82 90 0 0 1")):
    rc, out, err = run("carve", head, "--shape", "plane", "--pose", pose,
                       "--rays", "6", "--verify", "--verify-geometry", "--json")
    check(rc == 0, f"carve plane {label} --verify --verify-geometry: rc={rc} {err.strip()[:300]}")
    if rc == 0:
        p = json.loads(out)["runs"][0]["poses"][0]
        g = p["geometry"]
        check(p["max_abs_difference"] == 0 and g["wrong_inside"] == 0 and g["wrong_outside"] == 0
              and g["must_be_inside"] > 0 and g["must_be_outside"] > 0,
              f"plane {label}: exact and right against the half-space: {g}")
        plane_counts[label] = (p["counts"]["clipped"], p["counts"]["affected"])
check(len(plane_counts) == 5 and plane_counts["a"] == plane_counts["b"] == plane_counts["e"] and
      plane_counts["d"] != plane_counts["a"],
      f"plane: any pose scale gives the same sets, a turned plane others: {plane_counts}")
rc, out, err = run("carve", head, "--shape", "plane", "--rays", "6", "--pose",
                   "-300 500 82 20 0 0 0.1", "--verify", "--verify-geometry")
check(rc == 0, f"carve plane with the default size far outside at scale 0.1: "
               f"rc={rc} {err.strip()[:300]}")
# A plane has no size: --size with it is refused (a trial's --size 1 made
# a slab 2 units thick that cut nothing a half-space cuts: 28 800 voxels
# wrong by --verify-geometry, and cao render drew the volume uncut).
for command in (["carve", head, "--rays", "6"], ["render", head, "-o", os.path.join(tmp, "p_%d.png")]):
    expect_error(command + ["--shape", "plane", "--size", "20"], 2,
                 "--shape plane is the half-space", command[0] + ": --size with --shape plane")
# A real mesh at scale 3.8 (held-out: 2,811 voxels wrong), exact with 3 layers;
# with 1 layer its concave parts are merged into one interval, and the
# geometry check sees it (exit 3): the negative control.
rc, out, err = run("carve", head, "--mesh", bunny, "--pose", "94 120 82 10 20 30 380",
                   "--pose", "80 110 70 0 0 0 380", "--layers", "3", "--rays", "6", "--verify",
                   "--verify-geometry")
check(rc == 0, f"carve Bunny.vtp at scale 380, 3 layers, --verify-geometry: rc={rc} {err.strip()[:300]}")
rc, out, err = run("carve", head, "--mesh", bunny, "--pose", "94 120 82 10 20 30 380",
                   "--layers", "1", "--rays", "6", "--verify-geometry")
check(rc == 3 and "--verify-geometry" in err and "geometry: voxel" in out,
      f"negative control: 1 layer, the geometry check fails with exit 3: rc={rc} {err.strip()[:200]}")

# Bad input: a clear error, exit 2, nothing written.
tiny_raw = os.path.join(tmp, "tiny.raw")
with open(tiny_raw, "wb") as f:
    f.write(bytes(64))
for dims, words in (("100000 100000 100000", "above the limit of 2^31-1"),
                    ("600 600 600", "the data is short")):
    mhd = os.path.join(tmp, "claim.mhd")
    with open(mhd, "w") as f:
        f.write(f"NDims = 3\nDimSize = {dims}\nElementType = MET_UCHAR\nElementDataFile = tiny.raw\n")
    out_vti = os.path.join(tmp, "never.vti")
    expect_error(["lao", mhd, "-o", out_vti], 2, words, f".mhd claiming {dims} with 64 bytes")
    check(not os.path.exists(out_vti), f".mhd claiming {dims}: nothing written")
full_vti = os.path.join(tmp, "appended.vti")
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter  # noqa: E402
slc = vtkSLCReader()
slc.SetFileName(neghip)
wi = vtkXMLImageDataWriter()
wi.SetInputConnection(slc.GetOutputPort())
wi.SetFileName(full_vti)
wi.SetDataModeToAppended()
wi.EncodeAppendedDataOff()
wi.Write()
whole = open(full_vti, "rb").read()
cut_vti = os.path.join(tmp, "cut.vti")
with open(cut_vti, "wb") as f:
    f.write(whole[:int(0.8 * len(whole))])
rc, out, err = run("lao", full_vti, "--rays", "6")
check(rc == 0, f"an appended-raw .vti reads: rc={rc} {err.strip()[:200]}")
expect_error(["lao", cut_vti, "--rays", "6"], 2, "the file is short", "a .vti cut at 80%")
# An ASCII legacy .vtk cut in its values or in its header: the values it
# needs and holds (VTK's own messages were "Error reading ascii data" and
# "Cannot read scalar header!"); the whole file reads.
from vtkmodules.vtkIOLegacy import vtkDataSetWriter  # noqa: E402
ascii_vtk = os.path.join(tmp, "ascii.vtk")
asc_reader = vtkXMLImageDataReader()
asc_reader.SetFileName(small_volume("asc.vti"))
asc_reader.Update()
wl = vtkDataSetWriter()
wl.SetInputData(asc_reader.GetOutput())
wl.SetFileName(ascii_vtk)
wl.SetFileTypeToASCII()
wl.Write()
text = open(ascii_vtk, "rb").read()
head = text[:text.index(b"LOOKUP_TABLE")]
for cut, what in ((len(text) * 2 // 3, "in its values"), (len(head) - 3, "in its SCALARS line")):
    short_vtk = os.path.join(tmp, "short.vtk")
    with open(short_vtk, "wb") as f:
        f.write(text[:cut])
    expect_error(["lao", short_vtk, "--rays", "6"], 2, "ASCII values but the file holds",
                 f"an ASCII legacy .vtk cut {what}")
rc, out, err = run("lao", ascii_vtk, "--rays", "6")
check(rc == 0, f"the control: the whole ASCII legacy .vtk reads: rc={rc} {err.strip()[:200]}")
expect_error(["carve", neghip, "--path", "1000000000"], 2, "1 to 100000", "--path 1e9")
expect_error(["lao", neghip, "--samples", "1000000000"], 2, "2 to 65536", "--samples 1000000000")
expect_error(["lao", neghip, "--samples", "1e9"], 2, "2 to 65536", "--samples 1e9")
# A right name in another case says so (a re-trial got the bare list).
expect_error(["lao", neghip, "--variation", "Rotate"], 2, "the names are lower case: 'rotate'", "--variation Rotate")
expect_error(["lao", neghip, "--backend", "CPU"], 2, "the names are lower case: 'cpu'", "--backend CPU")
expect_error(["carve", neghip, "--shape", "Sphere"], 2, "the names are lower case: 'sphere'", "--shape Sphere")
# One sample per ray sees no occluder (a trial got AO 1 everywhere): refused.
expect_error(["lao", neghip, "--samples", "1"], 2, "2 to 65536", "--samples 1")
expect_error(["lao", neghip, "--rays", "fib:100000"], 2, "1 to 65536", "--rays fib:100000")
expect_error(["render", neghip, "--aa", "64", "-o", os.path.join(tmp, "x_%d.png")], 2, "0 to 32",
             "render --aa 64")
nan_mesh = os.path.join(tmp, "nan.vtp")
bad = vtkPolyData()
bad.DeepCopy(sphere.GetOutput())
bad.GetPoints().SetPoint(5, float("nan"), 0, 0)
wv.SetInputData(bad)
wv.SetFileName(nan_mesh)
wv.Write()
expect_error(["carve", neghip, "--mesh", nan_mesh], 2, "NaN or infinite coordinate",
             "a NaN vertex is not 'mesh is open'")
# cao surface names the file and the point (it said only "the mesh has a
# NaN or infinite coordinate", with several meshes given).
expect_error(["surface", os.path.join(data, "Bunny.vtp"), nan_mesh, "-o", os.path.join(tmp, "n.png")], 2,
             "nan.vtp': point 5 has a NaN or infinite coordinate", "surface names the mesh with a NaN point")
# A clip sphere 10^4 across around a 66^3 volume: maps only where the volume
# is (held-out: 2 min and 1.66 GB for a 4096^2 map, and a wrong message at 10^3).
import time  # noqa: E402
for size in ("1000", "10000"):
    start = time.time()
    rc, out, err = run("carve", neghip, "--shape", "sphere", "--size", size, "--pose",
                       f"{-float(size) + 30} 33 33", "--rays", "6", "--verify", "--json")
    took = time.time() - start
    check(rc == 0 and json.loads(out)["runs"][0]["poses"][0]["counts"]["clipped"] > 1000,
          f"a sphere of size {size} around neghip: rc={rc} ({took:.1f} s) {err.strip()[:200]}")
# Help per command, the offset default, lao --json's backend.
for command, words in (("lao", "--offset"), ("carve", "--verify-geometry"), ("render", "--image")):
    rc, out, err = run(command, "--help")
    check(rc == 0 and words in out, f"cao {command} --help: rc={rc} {err.strip()[:100]}")
rc, out, err = run("lao", "--help")
check("default 0.5: mid-step" in out and "default 0;" not in out, "--help gives the offset default 0.5")
rc, out, err = run("lao", neghip, "--rays", "rubiks54", "--reach", "4", "--json")
check(rc == 0 and json.loads(out)["pattern"] == "rubiks54" and json.loads(out)["rays"] == 54 and
      json.loads(out)["backend"] in ("cpu", "gl") and "context" in json.loads(out) and
      "backend_detail" in json.loads(out),
      f"lao --rays rubiks54 --json reports the pattern, the backend and the context: {out.strip()[:300]}")

# Progress on stderr when it is a terminal (a pty here), never in a pipe;
# a run longer than 2 s also says the time it has left, at the rate so far
# (the LAO's percentage, the carve path's pose count).
import pty  # noqa: E402
import threading  # noqa: E402


def on_terminal(*args):
    master, slave = pty.openpty()
    shown = []

    def read():
        try:
            while True:
                chunk = os.read(master, 4096)
                if not chunk:
                    break
                shown.append(chunk)
        except OSError:
            pass
    reader = threading.Thread(target=read)
    reader.start()
    p = subprocess.run([tool, *args], stdout=subprocess.PIPE, stderr=slave, timeout=600)
    os.close(slave)
    reader.join(timeout=10)
    os.close(master)
    return p.returncode, b"".join(shown).decode(errors="replace").replace("\r", "\n")


rc, shown = on_terminal("lao", neghip, "--rays", "fib:200")
check(rc == 0 and "LAO:" in shown and "%" in shown, f"a terminal shows the LAO's progress: {shown[-200:]!r}")
left = re.compile(r"\(about [0-9.]+ (s|min|h|days) left\)")
for what, args in (("the LAO", ["lao", neghip, "--rays", "fib:200", "--samples", "64", "--threads", "1"]),
                   ("the carve path", ["carve", neghip, "--rays", "fib:200", "--verify", "--path", "8",
                                       "--threads", "1"])):
    rc, shown = on_terminal(*args)
    lines = [line.strip() for line in shown.splitlines() if line.strip()]
    check(rc == 0 and any(left.search(line) for line in lines),
          f"{what}, longer than 2 s on a terminal, says the time it has left: rc={rc} {lines[-4:]}")
rc, out, err = run("lao", neghip, "--rays", "fib:200")
check(rc == 0 and "LAO:" not in err, "a pipe gets no progress line")

# cao tf: a transfer-function edit updated in place, against a full LAO.
# (A local edit: the opacity of the scalars above 240 only; an edit that
# reaches most voxels marches them all.)
rc, out, err = run("tf", neghip, "--from", "0,0,100,0,101,0.8,255,0.8", "--to",
                   "0,0,100,0,101,0.8,240,0.8,255,1", "--rays", "14", "--verify", "--json")
t = json.loads(out) if rc == 0 else {}
check(rc == 0 and t.get("update") == "opacity edit" and t.get("max_diff") == 0 and
      t.get("differing_voxels") == 0 and 0 < t.get("changed_voxels", 0) <= t.get("recomputed_voxels", 0) <
      t.get("voxels", 0) and t.get("full_ms", 0) > 0 and t.get("update_ms", 0) > 0,
      f"tf --verify: the edit equals the full LAO and recomputes fewer voxels: {out.strip()[:400]} {err[-200:]}")
rc, out, err = run("tf", neghip, "--from", "0,0,255,0.8", "--to", "0,0,191,0.6,255,0.8", "--rays", "14",
                   "--verify", "--json")
t = json.loads(out) if rc == 0 else {}
check(rc == 0 and t.get("max_diff") == 0 and t.get("recomputed_voxels") == t.get("voxels"),
      f"tf reaching most voxels marches them all, exactly: {out.strip()[:300]}")
rc, out, err = run("tf", neghip, "--from", "0,0,255,0.8", "--to", "0,0,255,0.8", "--json")
t = json.loads(out) if rc == 0 else {}
check(rc == 0 and t.get("changed_voxels") == 0 and t.get("recomputed_voxels") == 0,
      f"tf with no change recomputes nothing: {out.strip()[:300]}")
rc, out, err = run("tf", neghip, "--from", "0,0,255,0.8", "--to", "0,0,255,0.8")
check(rc == 0 and "voxels recomputed" in out and "max|diff|" in out, f"tf prints a table: {out[:300]}")
expect_error(["tf", neghip, "--from", "0,0,255,0.8"], 2, "--to is required", "tf without --to")
expect_error(["tf", neghip, "--from", "0,0,255,0.8", "--to", "0,0,255,5"], 2, "0 to 1",
             "tf with an opacity above 1")
expect_error(["tf", neghip, "--from", "0,0,255,0.8", "--to", "0,0,255"], 2, "pairs", "tf with an odd list")
# Scalars out of order or repeated were sorted or collapsed without a word
# (a trial's --to 1,0,0,1 and 0,0,0,1 ran; the control, in order, above).
for points in ("1,0,0,1", "0,0,0,1"):
    expect_error(["tf", neghip, "--from", "0,0,255,0.8", "--to", points], 2, "increasing scalar order",
                 "tf --to %s (a scalar not above the one before)" % points)
expect_error(["tf", neghip, "--from", "0,0,255,0.8", "--to", "0,0,255,1", "--backend", "gl"], 2,
             "CPU", "tf on the GPU")

# Silent results (the bad-input issue): each is now an error or a warning.
from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402


def write_volume(name, dims, spacing=(1.0, 1.0, 1.0), value=None):
    im = vtkImageData()
    im.SetDimensions(*dims)
    im.SetSpacing(*spacing)
    im.AllocateScalars(3, 1)  # unsigned char
    a = vtk_to_numpy(im.GetPointData().GetScalars())
    a[:] = value if value is not None else (np.arange(a.size) * 37 % 256)
    w = vtkXMLImageDataWriter()
    w.SetInputData(im)
    w.SetFileName(os.path.join(tmp, name))
    w.Write()
    return os.path.join(tmp, name)


# A volume with NaN scalars: cao tf runs the LAO filter three times (the
# --from LAO, the edit, the full recompute), and the warning that NaN reads
# as transparent is printed once (it was printed three times). Control: the
# warning is there, with its count.
nan_im = vtkImageData()
nan_im.SetDimensions(24, 24, 24)
nan_im.AllocateScalars(10, 1)  # float
nan_a = vtk_to_numpy(nan_im.GetPointData().GetScalars())
nan_a[:] = (np.arange(nan_a.size) * 37 % 256).astype(np.float32)
nan_a[:500:7] = np.nan
nan_w = vtkXMLImageDataWriter()
nan_w.SetInputData(nan_im)
nan_w.SetFileName(os.path.join(tmp, "nan.vti"))
nan_w.Write()
rc, out, err = run("tf", os.path.join(tmp, "nan.vti"), "--from", "0,0,255,0.8", "--to", "0,0,200,0,255,0.8",
                   "--rays", "6", "--verify")
check(rc == 0 and err.count("NaN or Inf") == 1 and "72 NaN or Inf scalar value(s)" in err,
      f"tf on NaN scalars warns once, with the count: rc={rc} {err.strip()[:400]!r}")
# One infinite voxel is transparent, as a NaN one, and no more: the default
# opacity ramp spans the finite values (over [min, inf] it left every voxel
# at opacity 0: AO 1 everywhere). Control: the same volume without it.
inf_a = nan_a.copy()
inf_a[np.isnan(inf_a)] = 0.0
ao_min = {}
for name, value in (("finite.vti", None), ("inf.vti", np.inf), ("neginf.vti", -np.inf)):
    nan_a[:] = inf_a
    if value is not None:
        nan_a[123] = value
    nan_im.GetPointData().GetScalars().Modified()
    nan_w.SetFileName(os.path.join(tmp, name))
    nan_w.Write()
    rc, out, err = run("lao", os.path.join(tmp, name), "--rays", "6", "--json")
    ao_min[name] = json.loads(out)["ao_range"][0] if rc == 0 else None
check(ao_min["finite.vti"] is not None and ao_min["finite.vti"] < 0.9 and
      all(ao_min[n] is not None and abs(ao_min[n] - ao_min["finite.vti"]) < 0.05 for n in ("inf.vti", "neginf.vti")),
      f"one infinite voxel leaves the default opacity map as it is: AO minimum {ao_min}")

# bench accuracy on an 8^3 volume: its clip sphere (radius 1.75 voxels) is
# narrower than the default depth-map pixels of 4 and 2 voxels; those rows
# are skipped, saying why, and the rest runs (it failed at the end).
tiny = write_volume("tiny_8.vti", (8, 8, 8))
rc, out, err = run("bench", "accuracy", tiny, "--patterns", "6", "--densities", "1", "--variants", "paper",
                   "--storage", "float32", "--backends", "cpu", "--reference-rays", "64", "--no-step-check",
                   "-o", os.path.join(tmp, "bench_tiny"))
check(rc == 0 and "skipped: a pixel of 4 voxels is wider than the sphere's radius" in out and
      re.search(r"^1 +cpu +[0-9.]+", out, re.M),
      f"bench accuracy on 8^3 skips the map pixels wider than its sphere: rc={rc} {err.strip()[-300:]!r}")

# A volume one voxel thick is a slab: its in-plane rays see its matter, so
# its AO is below 1 (the filters' hard-cases test has the exact value of an
# opaque slab); reported once as exactly 1 everywhere.
for dims in ((32, 32, 1), (1, 32, 32)):
    flat = write_volume("flat_%d_%d_%d.vti" % dims, dims)
    rc, out, err = run("lao", flat, "--json")
    lo = json.loads(out)["ao_range"][0] if rc == 0 else 1.0
    check(rc == 0 and lo < 0.9, f"lao on a {dims} slab darkens it (lowest AO {lo}): {err.strip()[:200]}")
rc, out, err = run("lao", write_volume("thin.vti", (32, 32, 2)), "--json")
check(rc == 0, f"a 32x32x2 volume runs: rc={rc} {err.strip()[:200]}")
# Tiny spacing: the default sphere is a quarter of the volume's smallest
# extent, not floored at 1e-6 (which clipped every voxel).
tiny = write_volume("tiny.vti", (24, 24, 24), spacing=(1e-9, 1e-9, 1e-9))
rc, out, err = run("carve", tiny, "--path", "1", "--json")
t = json.loads(out) if rc == 0 else {}
try:
    clipped = t["runs"][0]["poses"][0]["counts"]["clipped"]
except (KeyError, IndexError, TypeError):
    clipped = -1
check(rc == 0 and 0 < clipped < 24 ** 3,
      f"spacing 1e-9: the default sphere clips part of the volume, not all ({clipped} of {24 ** 3}): "
      f"{out.strip()[:200]} {err.strip()[:200]}")
frame = os.path.join(tmp, "f_%d.png")
expect_error(["render", neghip, "--sample-distance", "0", "-o", frame], 2, "positive length",
             "render --sample-distance 0")
expect_error(["render", neghip, "--sample-distance", "1e-9", "-o", frame], 2, "1/200 of the smallest",
             "render --sample-distance 1e-9")
expect_error(["render", neghip, "--shape", "cube", "--mesh", os.path.join(data, "Bunny.vtp"), "-o", frame],
             2, "--shape excludes --mesh", "render --shape with --mesh")
expect_error(["carve", neghip, "--shape", "cube", "--mesh", os.path.join(data, "Bunny.vtp")], 2,
             "--shape excludes --mesh", "carve --shape with --mesh")
expect_error(["render", neghip, "--no-clip", "--shape", "torus", "-o", frame], 2, "--no-clip",
             "render --no-clip with --shape")
# Scale and place do not change the picture: neghip at spacing 1e-6 (with
# its opacities referring to 1e-6) and at an origin of 1e10 and 1e15 renders
# as at spacing 1 and origin 0 (blank frames with exit 0 before: OpenGL's
# float camera). The control: spacing 1e-6 under the default unit distance
# is nearly transparent, and a warning says why.
from vtkmodules.vtkIOImage import vtkPNGReader, vtkSLCReader as _SLC
from vtkmodules.vtkImagingCore import vtkImageChangeInformation


def moved(name, spacing, origin):
    r = _SLC()
    r.SetFileName(neghip)
    c = vtkImageChangeInformation()
    c.SetInputConnection(r.GetOutputPort())
    c.SetOutputSpacing(spacing, spacing, spacing)
    c.SetOutputOrigin(origin, origin, origin)
    w = vtkXMLImageDataWriter()
    w.SetInputConnection(c.GetOutputPort())
    w.SetFileName(os.path.join(tmp, name))
    w.Write()
    return os.path.join(tmp, name)


def grey(png):
    r = vtkPNGReader()
    r.SetFileName(png)
    r.Update()
    return vtk_to_numpy(r.GetOutput().GetPointData().GetScalars()).astype(float)


def render_one(volume, *extra):
    out = os.path.join(tmp, "scale_%d.png")
    rc, _, err = run("render", volume, "--path", "1", "--image", "96x96", *extra, "-o", out)
    return rc, err, grey(out % 0) if rc == 0 else None


rc, err, reference = render_one(neghip)
no_gl = rc == 125 or "no EGL" in err
if no_gl:
    check(os.environ.get("CAO_REQUIRE_GL", "0") in ("", "0"),
          "render ran (CAO_REQUIRE_GL is set): rc=%d %s" % (rc, err.strip()[:200]))
for what, volume, extra in [] if no_gl else (("spacing 1e-6", moved("tiny.vti", 1e-6, 0.0), ["--unit-distance", "1e-6"]),
                            ("origin 1e10", moved("far10.vti", 1.0, 1e10), []),
                            ("origin 1e15", moved("far15.vti", 1.0, 1e15), [])):
    rc, err, picture = render_one(volume, *extra)
    diff = np.abs(picture - reference) if picture is not None and reference is not None else None
    check(rc == 0 and diff is not None and diff.mean() < 0.05 and diff.max() <= 8,
          f"render at {what} is the picture at spacing 1, origin 0: rc={rc} "
          f"{'' if diff is None else (diff.mean(), diff.max())} {err.strip()[:200]!r}")
rc, err, picture = (0, "nearly transparent", reference + 10) if no_gl else \
    render_one(os.path.join(tmp, "tiny.vti"))
check(rc == 0 and "nearly transparent" in err and picture is not None and
      np.abs(picture - reference).mean() > 5,
      f"control: spacing 1e-6 with opacities referring to 1 is nearly empty, with a warning: {err.strip()[:200]!r}")

# Readers' own messages: one line, the file named, no VTK log line, no
# MetaIO console text, no "ERROR: In file, line" prefix.
def write(name, text, tail=b""):
    path = os.path.join(tmp, name)
    with open(path, "wb") as f:
        f.write(text.encode() + tail)
    return path


header = "ObjectType = Image\nNDims = 3\nDimSize = 4 4 4\n"
for path, command, words, what in (
        (write("badspacing.vtk", "# vtk DataFile Version 3.0\nx\nASCII\nDATASET STRUCTURED_POINTS\n"
               "DIMENSIONS 4 4 4\nSPACING 1 1\nORIGIN 0 0 0\nPOINT_DATA 64\n"), "lao",
         "Error reading spacing", "a legacy .vtk with two spacing values"),
        (write("twospacings.mhd", header + "ElementSpacing = 1 1\nElementType = MET_UCHAR\n"
               "ElementDataFile = LOCAL\n", bytes(64)), "lao", "2 ElementSpacing values for 3",
         "a .mhd with two spacing values"),
        (write("notype.mhd", header + "ElementDataFile = LOCAL\n", bytes(64)), "lao",
         "no ElementType", "a .mhd without ElementType"),
        (write("badtype.mhd", header + "ElementType = UCHAR\nElementDataFile = LOCAL\n", bytes(64)),
         "lao", "not a MetaImage type", "a .mhd with an unknown ElementType"),
        (write("cut.stl", "solid x\nfacet normal 0 0 1\n"), "carve", "Premature EOF",
         "an ASCII STL cut after its first facet line")):
    args = [command, path] if command == "lao" else [command, neghip, "--mesh", path]
    rc, out, err = run(*args)
    lines = [l for l in err.splitlines() if l.strip()]
    check(rc == 2 and len(lines) == 1 and words in err and os.path.basename(path) in err and
          "ERR|" not in err and "MetaObject" not in err and "MetaImage:" not in err and
          "ERROR: In" not in err,
          f"{what}: one line naming the file: rc={rc} {err.strip()[:300]!r}")
# The control: the same header, complete, reads.
rc, out, err = run("lao", write("complete.mhd", header + "ElementSpacing = 1 1 1\n"
                                "ElementType = MET_UCHAR\nElementDataFile = LOCAL\n", bytes(64)),
                   "--rays", "6")
check(rc == 0, f"a complete .mhd of the same header reads: rc={rc} {err.strip()[:200]!r}")

# Pose scales out of the clip's range: one line naming the pose, the scale and
# the range, before any VTK output (they failed inside vtkClipDepthMaps).
for command in (["carve", neghip], ["render", neghip, "-o", frame]):
    for scale, words in (("1e9", "over 2^23 voxels"), ("1e-9", "under half a voxel")):
        rc, out, err = run(*command, "--pose", "30 30 30 0 0 0 " + scale)
        lines = [l for l in err.splitlines() if l.strip()]
        check(rc == 2 and len(lines) == 1 and words in err and "the scale must lie in" in err and
              "ERR|" not in err and "WARN|" not in err,
              f"{command[0]} --pose scale {scale}: one clear line: rc={rc} {err.strip()[:300]!r}")
# --size out of range is said as a size (a trial's --size 1e30 was told
# "scale 1 ... the scale must lie in [2.5e-31, 4.1943e-24]", a scale it
# never gave); the control: a size inside the stated range carves.
for size, words in (("1e30", "over 2^23 voxels"), ("0.1", "under half a voxel")):
    rc, out, err = run("carve", neghip, "--shape", "cube", "--size", size, "--path", "3", "--rays", "6")
    lines = [l for l in err.splitlines() if l.strip()]
    check(rc == 2 and len(lines) == 1 and words in err and "--size must lie in [0.25, " in err and
          "scale" not in err, f"carve --size {size}: one line in terms of --size: rc={rc} {err.strip()[:300]!r}")
rc, out, err = run("carve", neghip, "--shape", "cube", "--size", "0.3", "--path", "3", "--rays", "6")
check(rc == 0, f"carve --size 0.3 (inside the stated range) runs: rc={rc} {err.strip()[:200]!r}")
# The default path of 2 poses starts and ends outside the volume: the note
# says so (a trial was told the 16-voxel sphere was "about as small as a
# voxel"); at 8 poses it carves and there is no such note (the control).
rc, out, err = run("carve", neghip, "--path", "2", "--rays", "6")
check(rc == 0 and "lies outside the volume, or only grazes it" in err and "as small as a voxel" not in err,
      f"carve --path 2: the note says the shape lies outside: rc={rc} {err.strip()[:300]!r}")
rc, out, err = run("carve", neghip, "--path", "8", "--rays", "6")
check(rc == 0 and "outside the volume" not in err and "as small as a voxel" not in err,
      f"carve --path 8 carves without that note: rc={rc} {err.strip()[:300]!r}")
# A pose far from the volume (a trial's 1e20 said "the clipping camera has
# zero area", a plane's "the shape size must be positive"): one line with
# its distance and the limit, from carve, render and a plane alike.
for command in (["carve", neghip], ["render", neghip, "-o", frame], ["carve", neghip, "--shape", "plane"]):
    for far in ("1e20 0 0", "1e300 0 0"):
        rc, out, err = run(*command, "--pose", far)
        lines = [l for l in err.splitlines() if l.strip()]
        check(rc == 2 and len(lines) == 1 and "from the volume; beyond 2^22 voxels" in err and "inf" not in err,
              f"{' '.join(command[:1] + command[2:3])} --pose {far}: one clear line: rc={rc} {err.strip()[:300]!r}")
# The control: a scale inside the range carves, and so does a pose just
# outside the volume (it clips nothing).
rc, out, err = run("carve", neghip, "--pose", "30 30 30 0 0 0 2", "--rays", "6")
check(rc == 0 and "reaches no voxel" not in err, f"carve --pose scale 2 runs: rc={rc} {err.strip()[:200]!r}")
rc, out, err = run("carve", neghip, "--pose", "300 30 30", "--rays", "6")
check(rc == 0 and "the clip shape reaches no voxel: nothing is clipped" in err,
      f"carve --pose outside the volume runs, and says it clips nothing: rc={rc} {err.strip()[:200]!r}")
const = write_volume("constant.vti", (16, 16, 16), value=7)
rc, out, err = run("lao", const, "--json")
check(rc == 0 and "warning" in err and "constant" in err,
      f"a constant volume is read, with a warning that the default map hides it: {err.strip()[:200]}")
rc, out, err = run("lao", thin := os.path.join(tmp, "thin.vti"), "--json")
check(rc == 0 and "warning" not in err, f"negative control: no warning for a volume that varies: {err[:200]}")
bad_dir = os.path.join(tmp, "not-a-folder")
open(bad_dir, "w").close()
rc, out, err = run("bench", "surface", os.path.join(data, "Bunny.vtp"), "--image", "32x32", "-o", bad_dir)
check(rc != 0 and "cannot write" in err and "wrote" not in out,
      f"bench surface -o to a place it cannot write: an error, no 'wrote': rc={rc} {err.strip()[:200]}")

# Floating-point scalars that single precision cannot hold as they are (far
# from 0 against their range, or a range of 1e20) are drawn as the same
# block is at its own values: they were a black silhouette (x 1e20) or a
# blank frame (+ 1e12, x 1e38). Control: the block itself.
from vtkmodules.vtkIOImage import vtkPNGReader  # noqa: E402
block = np.zeros((24, 24, 24))
block[6:18, 6:18, 4:20] = 200.0
block[10:14, 10:14, 14:20] = 0.0  # a slot
frames = {}
for name, values in (("block", block), ("block_1e20", block * 1e20), ("block_offset", block + 1e12),
                     ("block_1e38", block * 1e36)):
    im = vtkImageData()
    im.SetDimensions(24, 24, 24)
    a = numpy_to_vtk(values.ravel(), deep=1)
    a.SetName("s")
    im.GetPointData().SetScalars(a)
    w = vtkXMLImageDataWriter()
    w.SetInputData(im)
    w.SetFileName(os.path.join(tmp, name + ".vti"))
    w.Write()
    rc, out, err = run("render", os.path.join(tmp, name + ".vti"), "--no-clip", "--window", "egl", "--image",
                       "96x96", "-o", os.path.join(tmp, name + "_%d.png"))
    png = vtkPNGReader()
    png.SetFileName(os.path.join(tmp, name + "_0.png"))
    png.Update()
    frames[name] = (vtk_to_numpy(png.GetOutput().GetPointData().GetScalars()).astype(float)[:, :3]
                    if rc == 0 else None)
base = frames["block"]
for name in ("block_1e20", "block_offset", "block_1e38"):
    f = frames[name]
    diff = float(np.abs(f - base).mean()) if f is not None and base is not None else None
    check(diff is not None and diff < 1.0 and float(np.abs(base - base[0]).sum(1).max()) > 50,
          f"{name}: drawn as the block at its own values (mean difference {diff} of 255)")

# The default camera keeps a volume's box in the frame (a trial's carotid,
# 76 x 49 x 45 and matter to its edges, ran off three edges at the former
# fixed zoom 1.4): the frame's outer 2 pixels are background at the
# default, and an explicit --zoom 1.4 (the former default) is left alone and
# crosses them (the control).
filled = write_volume("filled.vti", (76, 49, 45))
edge_frames = {}
for label, extra in (("default", ()), ("zoom14", ("--zoom", "1.4"))):
    png = os.path.join(tmp, "filled_" + label + "_%d.png")
    rc, out, err = run("render", filled, "--no-clip", "--window", "egl", "--image", "120x120", *extra, "-o", png)
    edge_frames[label] = grey(png % 0)[:, :3].reshape(120, 120, 3) if rc == 0 else None
def border_hits(f):
    if f is None:
        return -1
    background = f[0, 0]
    ring = np.ones((120, 120), bool)
    ring[2:-2, 2:-2] = False
    return int((np.abs(f - background).max(axis=2)[ring] > 10).sum())
check(border_hits(edge_frames["default"]) == 0 and border_hits(edge_frames["zoom14"]) > 0,
      "render's default zoom keeps a 76 x 49 x 45 volume's box in the frame (%d border pixels drawn; "
      "%d at --zoom 1.4)" % (border_hits(edge_frames["default"]), border_hits(edge_frames["zoom14"])))

print(f"{passed} passed, {len(failures)} failed")
sys.exit(1 if failures else 0)

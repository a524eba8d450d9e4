#!/usr/bin/env bash
# README command 1: set up, build, then run the main job: render a clip
# sphere moving through a bundled real volume (Data/neghip.slc) with the
# contextual-AO volume mapper, in an offscreen EGL window (no X needed).
# Every pose of the path (Data/neghip-main.poses) cuts the volume. The 12
# frames are rendered with AO (each frame's work report in JSON) and
# without, and put side by side (AO off | AO on) to show what the AO adds.
# Then the mixed scene (Rendering/Scene/Demo/mixed_scene.py): carotid.vtk's
# volume, isosurface and streamline tubes, each with its AO, in one frame.
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/setup.sh
build="${BUILD_DIR:-build}"
out="$build/frames"
mkdir -p "$out"
"$build/bin/cao" render Data/neghip.slc --poses Data/neghip-main.poses --image 512x512 --zoom 1.4 \
  --window egl -o "$out/neghip_%03d.png" --json >"$out/report.json"
"$build/bin/cao" render Data/neghip.slc --poses Data/neghip-main.poses --image 512x512 --zoom 1.4 \
  --window egl --no-ao -o "$out/neghip_noao_%03d.png" >/dev/null
/usr/bin/python3 - "$out" <<'PY'
import sys
from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter
from vtkmodules.vtkImagingCore import vtkImageExtractComponents
from vtkmodules.vtkFiltersCore import vtkImageAppend
out = sys.argv[1]
for i in range(12):
    row = vtkImageAppend()
    for name in ("neghip_noao_%03d.png", "neghip_%03d.png"):
        r = vtkPNGReader()
        r.SetFileName(out + "/" + name % i)
        rgb = vtkImageExtractComponents()
        rgb.SetInputConnection(r.GetOutputPort())
        rgb.SetComponents(0, 1, 2)
        row.AddInputConnection(rgb.GetOutputPort())
    w = vtkPNGWriter()
    w.SetFileName(out + "/side_%03d.png" % i)
    w.SetInputConnection(row.GetOutputPort())
    w.Write()
PY
echo "wrote $out/neghip_000.png .. neghip_011.png (AO on), neghip_noao_*.png (AO off),"
echo "      side_000.png .. side_011.png (AO off | AO on) and $out/report.json"
# The mixed scene: carotid.vtk as a contextual-AO volume under a moving clip
# sphere, with an isosurface and streamline tubes, every kind with its AO in
# the same frame (the volume occluding the surfaces), AO off | AO on.
PYTHONPATH="$build/python" /usr/bin/python3 Rendering/Scene/Demo/mixed_scene.py \
  Data/carotid.vtk "$out" --frames 12 --image 640x480

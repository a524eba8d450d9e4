#!/usr/bin/env bash
# README command 1: set up, build, then run the main job: render a clip
# sphere moving through a bundled real volume (Data/neghip.slc) with the
# contextual-AO volume mapper, in an offscreen EGL window (no X needed):
# 12 PNG frames and each frame's work report (JSON).
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/setup.sh
build="${BUILD_DIR:-build}"
mkdir -p "$build/frames"
"$build/bin/cao" render Data/neghip.slc --path 12 --image 512x512 --window egl \
  -o "$build/frames/neghip_%03d.png" --json >"$build/frames/report.json"
echo "wrote $build/frames/neghip_000.png .. neghip_011.png and $build/frames/report.json"

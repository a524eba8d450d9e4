#!/usr/bin/env bash
# README command 1: set up, build, then run the main job: contextual AO on a
# bundled real volume (Data/neghip.slc) while a clip sphere moves along a
# 24-pose path, every pose verified against a full LAO recompute; prints
# the per-pose table and writes the last AO volume.
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/setup.sh
build="${BUILD_DIR:-build}"
"$build/bin/cao" carve Data/neghip.slc --shape sphere --rays 26 --path 24 --verify \
  -o "$build/cao-last-pose.vti"
echo "wrote $build/cao-last-pose.vti"

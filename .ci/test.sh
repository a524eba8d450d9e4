#!/usr/bin/env bash
# README command 2: set up, build, then run the whole test suite (ctest).
# Exits non-zero on any failure.
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/setup.sh
build="${BUILD_DIR:-build}"
cd "$build"
ctest --output-on-failure -j2 --timeout 1500

#!/usr/bin/env bash
# Render the plugin's representation with one of ParaView's executables
# under a private Xvfb, then compare the screenshot with its baseline with
# OpenImageIO's idiff (a pixel fails above 4/255; at most 0.25% may fail,
# as in the mapper's image tests). CAO_UPDATE_BASELINES=1 writes the
# baseline instead (check it by eye before committing it).
#   test-screenshot.sh pvpython|pvbatch|paraview PLUGIN.so DATA_DIR BASELINE.png OUTPUT.png
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
exe=$1
export CAO_PLUGIN=$2 CAO_DATA_DIR=$3 CAO_SCREENSHOT=$5
baseline=$4
rm -f "$CAO_SCREENSHOT" "$CAO_SCREENSHOT.done"
command -v "$exe" >/dev/null || { echo "SKIP: no $exe executable"; exit 125; }
script="$here/render_representation.py"
if [ "$exe" = paraview ]; then
  export CAO_GUI=1
  args=(--dr --script="$script")
else
  args=(--dr "$script")
fi
timeout 300 bash "$here/../../Testing/run-with-xvfb.sh" "$exe" "${args[@]}" >"$CAO_SCREENSHOT.log" 2>&1 || true
[ -f "$CAO_SCREENSHOT.done" ] || { echo "FAIL: the $exe script did not finish:"; cat "$CAO_SCREENSHOT.log"; exit 1; }
if grep -q "ERR|" "$CAO_SCREENSHOT.log"; then
  echo "FAIL: errors while rendering:"; grep "ERR|" "$CAO_SCREENSHOT.log"; exit 1
fi
if [ "${CAO_UPDATE_BASELINES:-0}" = 1 ]; then
  cp "$CAO_SCREENSHOT" "$baseline"
  echo "wrote baseline $baseline"
  exit 0
fi
idiff -fail 0.0157 -failpercent 0.25 "$CAO_SCREENSHOT" "$baseline"

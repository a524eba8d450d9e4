#!/usr/bin/env bash
# The plugin in the ParaView GUI: start `paraview` under a private Xvfb with
# a startup script that loads the plugin, applies the LAO filter, saves a
# screenshot and quits; then compare the screenshot with its baseline with
# OpenImageIO's idiff (a pixel fails above 4/255; at most 0.25% may fail,
# as in the mapper's image tests).
#   test-gui.sh PLUGIN.so DATA_DIR BASELINE.png OUTPUT_PREFIX
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
export CAO_PLUGIN=$1 CAO_DATA_DIR=$2 CAO_GUI_OUTPUT=$4
baseline=$3
rm -f "$CAO_GUI_OUTPUT.png" "$CAO_GUI_OUTPUT.txt"
command -v paraview >/dev/null || { echo "SKIP: no paraview executable"; exit 125; }
timeout 300 bash "$here/../../Testing/run-with-xvfb.sh" paraview --script="$here/gui_lao.py" \
  >"$CAO_GUI_OUTPUT.log" 2>&1 || true
[ -f "$CAO_GUI_OUTPUT.txt" ] || { echo "FAIL: the GUI script did not finish:"; cat "$CAO_GUI_OUTPUT.log"; exit 1; }
if [ "${CAO_UPDATE_BASELINES:-0}" = 1 ]; then
  cp "$CAO_GUI_OUTPUT.png" "$baseline"
  echo "wrote baseline $baseline"
  exit 0
fi
idiff -fail 0.0157 -failpercent 0.25 "$CAO_GUI_OUTPUT.png" "$baseline"

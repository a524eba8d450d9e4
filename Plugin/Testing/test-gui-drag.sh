#!/usr/bin/env bash
# The clip widget dragged as a user drags it: real X pointer events
# (xdotool) into the ParaView GUI under a private Xvfb, at ParaView's
# default settings, with translucent geometry in the view (a translucent
# sphere, and the widget's own face while it is dragged), so that VTK draws
# the volume inside its dual depth peeling. TestClipDragGUI.py sets the
# scene up and logs every frame, mouse move and mapper error; this script
# finds the render view on the screen from the moves the view received,
# drags the widget's centre handle, then its face, then the box with the
# middle button (which moves it from anywhere on it, in any view), each for
# about 2.5 s, waits until the GUI draws no more, and checks the log:
# - no mapper error, and no ray-cast or GL-state error in the GUI's log;
# - frames drawn for each drag, some inside the depth peeling;
# - the drag moved (centre, middle button) and turned (face) the clip, and the last frame
#   draws the clip at the pose the widget shows.
# It prints what the user saw: frames during the drag and the time from the
# release to the last frame (measured, never asserted).
# With SCRIPT.py and CHECK.py, another scene's drags and checks
# (TestLinesDragGUI.py: the camera turned over streamlines).
# With CAO_SERVER_URL set, the GUI connects to that server first (a
# pvserver started by hand: a trial, docs/interaction.md).
#   test-gui-drag.sh PLUGIN.so DATA_DIR RESULT_BASE [SCRIPT.py CHECK.py]
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
export PYTHONPATH="$here${PYTHONPATH:+:$PYTHONPATH}" # clip_widget_pose.py
command -v paraview >/dev/null || { echo "SKIP: no paraview executable"; exit 125; }
command -v xdotool >/dev/null || { echo "FAIL: xdotool is missing (.ci/setup.sh installs it)"; exit 1; }
export CAO_PLUGIN=$1 CAO_DATA_DIR=$2 CAO_RESULT=$3
rm -f "$CAO_RESULT".*
timeout 900 bash "$here/../../Testing/run-with-xvfb.sh" bash "$here/gui-drag-driver.sh" \
  "$here/${4:-TestClipDragGUI.py}" >"$CAO_RESULT.log" 2>&1
status=$?
cat "$CAO_RESULT.log" | grep -E "^(driver|ok|FAIL|PASSED|FAILED)" || true
if [ "$status" -ne 0 ]; then
  echo "FAIL: the driver exited with $status; its log:"
  tail -40 "$CAO_RESULT.log"
  exit 1
fi
if grep -E "Error in cache state|The ray cast failed" "$CAO_RESULT.gui.log"; then
  echo "FAIL: the GUI's log has OpenGL state or ray-cast errors (above)"
  exit 1
fi
/usr/bin/python3 "$here/${5:-gui-drag-check.py}" "$CAO_RESULT"

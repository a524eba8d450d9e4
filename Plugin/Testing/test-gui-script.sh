#!/usr/bin/env bash
# Run a GUI startup script in the ParaView GUI under a private Xvfb and pass
# when the result file it writes ends with PASSED (skip: SKIPPED, 125) and the GUI's log has no
# VTK GL-state ("Error in cache state") or ray-cast errors.
#   test-gui-script.sh SCRIPT.py PLUGIN.so DATA_DIR RESULT.txt
set -uo pipefail
script=$1
export CAO_PLUGIN=$2 CAO_DATA_DIR=$3 CAO_RESULT=$4
here=$(cd "$(dirname "$0")" && pwd)
export PYTHONPATH="$here${PYTHONPATH:+:$PYTHONPATH}" # clip_widget_pose.py
command -v paraview >/dev/null || { echo "SKIP: no paraview executable"; exit 125; }
rm -f "$CAO_RESULT"
# (CAO_SERVER_URL: connect to that server first: test-gui-remote.sh.)
timeout 300 bash "$here/../../Testing/run-with-xvfb.sh" paraview --dr ${CAO_SERVER_URL:+--server-url="$CAO_SERVER_URL"} --script="$script" \
  >"$CAO_RESULT.log" 2>&1 || true
[ -f "$CAO_RESULT" ] || { echo "FAIL: the script wrote no result:"; cat "$CAO_RESULT.log"; exit 1; }
cat "$CAO_RESULT"
# VTK's own GL state checks and the mapper's errors go to the log: a frame
# that left the view's OpenGL state stale, or a ray cast that failed, fails.
if grep -E "Error in cache state|The ray cast failed" "$CAO_RESULT.log"; then
  echo "FAIL: the GUI's log has OpenGL state or ray-cast errors (above)"
  exit 1
fi
# A script that cannot run here says why and ends with SKIPPED.
if tail -n 1 "$CAO_RESULT" | grep -qx SKIPPED; then exit 125; fi
tail -n 1 "$CAO_RESULT" | grep -qx PASSED

#!/usr/bin/env bash
# Run a GUI startup script (test-gui-script.sh) in a GUI connected to a
# pvserver on 2 MPI processes (remote rendering), started here on a free
# port and stopped after (with-pvserver.sh).
#   test-gui-remote.sh SCRIPT.py PLUGIN.so DATA_DIR RESULT.txt
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
command -v paraview >/dev/null || { echo "SKIP: no paraview executable"; exit 125; }
exec bash "$here/with-pvserver.sh" "$4.server.log" bash "$here/test-gui-script.sh" "$@"

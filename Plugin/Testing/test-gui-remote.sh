#!/usr/bin/env bash
# Run a GUI startup script (test-gui-script.sh) in a GUI connected to a
# pvserver on 2 MPI processes (remote rendering), started here on a free
# port and stopped after.
#   test-gui-remote.sh SCRIPT.py PLUGIN.so DATA_DIR RESULT.txt
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
for tool in pvserver mpirun paraview; do
  command -v "$tool" >/dev/null || { echo "SKIP: no $tool executable"; exit 125; }
done
log="$4.server.log"
rm -f "$log"
for attempt in 1 2 3; do
  port=$((20000 + RANDOM % 20000))
  mpirun --allow-run-as-root --oversubscribe -np 2 \
    bash "$here/../../Testing/run-with-xvfb.sh" pvserver --sp="$port" >"$log" 2>&1 &
  server=$!
  for _ in $(seq 120); do
    grep -q "Accepting connection" "$log" 2>/dev/null && break
    kill -0 "$server" 2>/dev/null || break
    sleep 0.5
  done
  grep -q "Accepting connection" "$log" && break
  kill "$server" 2>/dev/null; wait "$server" 2>/dev/null
done
grep -q "Accepting connection" "$log" || { echo "FAIL: pvserver did not start:"; cat "$log"; exit 1; }
CAO_SERVER_URL="cs://localhost:$port" bash "$here/test-gui-script.sh" "$@"
status=$?
kill "$server" 2>/dev/null; wait "$server" 2>/dev/null
exit $status

#!/usr/bin/env bash
# Run COMMAND with a pvserver on 2 MPI processes (remote rendering, under
# its own Xvfb) started here on a free port, CAO_SERVER_URL set to it; the
# server is stopped after. Exits with COMMAND's status, 125 when pvserver or
# mpirun is missing, 1 when the server does not start.
#   with-pvserver.sh SERVER_LOG COMMAND [ARGS...]
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
for tool in pvserver mpirun; do
  command -v "$tool" >/dev/null || { echo "SKIP: no $tool executable"; exit 125; }
done
log=$1
shift
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
CAO_SERVER_URL="cs://localhost:$port" "$@"
status=$?
kill "$server" 2>/dev/null; wait "$server" 2>/dev/null
exit $status

#!/usr/bin/env bash
# Run TestHostContext.py in one of ParaView's executables under a private
# Xvfb; fail on a crash, an unfinished script, a failed check, or any error
# ParaView logged ("ERR|", "Error in cache state": the host's GL context
# gone stale).
#   test-host-context.sh pvpython|pvbatch|paraview PLUGIN.so DATA_DIR OUT_DIR view-first|filters-first
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
exe=$1
export CAO_PLUGIN=$2 CAO_DATA_DIR=$3 CAO_OUT=$4 CAO_ORDER=$5
command -v "$exe" >/dev/null || { echo "SKIP: no $exe executable"; exit 125; }
rm -rf "$CAO_OUT"
mkdir -p "$CAO_OUT"
script="$here/TestHostContext.py"
if [ "$exe" = paraview ]; then
  export CAO_GUI=1
  args=(--dr --script="$script")
else
  args=(--dr "$script")
fi
status=0
timeout 300 bash "$here/../../Testing/run-with-xvfb.sh" "$exe" "${args[@]}" >"$CAO_OUT/log.txt" 2>&1 || status=$?
grep -E "^(ok|FAIL):" "$CAO_OUT/log.txt" || true
if [ ! -f "$CAO_OUT/done.txt" ]; then
  echo "FAIL: $exe did not finish the script (exit $status):"
  tail -40 "$CAO_OUT/log.txt"
  exit 1
fi
if grep -qE "ERR\||Error in cache state" "$CAO_OUT/log.txt"; then
  echo "FAIL: $exe logged errors:"
  grep -E "ERR\||Error in cache state" "$CAO_OUT/log.txt" | head -20
  exit 1
fi
if [ "$(head -1 "$CAO_OUT/done.txt")" != ok ]; then
  echo "FAIL: checks failed:"; cat "$CAO_OUT/done.txt"; exit 1
fi
echo "$exe, $CAO_ORDER: every backend ran, the view rendered, nothing logged"

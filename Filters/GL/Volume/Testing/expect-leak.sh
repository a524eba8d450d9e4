#!/usr/bin/env bash
# Negative control of the LeakSanitizer run: the test binary, with a leak
# injected (CAO_TEST_INJECT_LEAK=1 in the environment), must fail and say
# that LeakSanitizer found it. Exits 0 when it does, 1 when the leak went
# unseen, 125 when the test itself skipped (no OpenGL 4.3 context).
#   expect-leak.sh TEST_BINARY ARGS...
set -uo pipefail
out=$("$@" 2>&1)
status=$?
if [ "$status" -eq 125 ]; then
  echo "$out" | tail -3
  exit 125
fi
if [ "$status" -ne 0 ] && echo "$out" | grep -q "LeakSanitizer found leaks" &&
  echo "$out" | grep -q "InjectLeak"; then
  echo "the injected leak was caught (exit $status):"
  echo "$out" | grep -m3 -E "Direct leak|InjectLeak"
  exit 0
fi
echo "FAIL: the injected leak was not caught (exit $status):"
echo "$out" | tail -20
exit 1

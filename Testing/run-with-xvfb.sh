#!/usr/bin/env bash
# Run a command under a private Xvfb server: the tests' stand-in for
# xvfb-run. Xvfb picks a free display itself and reports it through
# -displayfd once it accepts connections, so parallel tests cannot race for
# a display number.
# -noreset: by default an X server resets when its last client disconnects
# and refuses connections meanwhile. A test that opens and closes the
# display (VTK's SupportsOpenGL probe) and then opens it again hit that
# window now and then ("bad X server connection"); without -noreset a
# loop of XOpenDisplay/XCloseDisplay fails on its 2nd or 3rd open here.
#   run-with-xvfb.sh COMMAND [ARGS...]
set -euo pipefail
fifo_dir=$(mktemp -d)
trap 'kill "${xvfb_pid:-0}" 2>/dev/null || true; wait "${xvfb_pid:-0}" 2>/dev/null || true; rm -rf "$fifo_dir"' EXIT
mkfifo "$fifo_dir/display"
Xvfb -displayfd 3 -screen 0 1024x768x24 -nolisten tcp -noreset \
  3>"$fifo_dir/display" 2>"$fifo_dir/log" &
xvfb_pid=$!
if ! read -r -t 30 display <"$fifo_dir/display" || [ -z "$display" ]; then
  echo "run-with-xvfb: Xvfb did not start:" >&2
  cat "$fifo_dir/log" >&2
  exit 1
fi
status=0
DISPLAY=":$display" "$@" || status=$?
if [ "$status" -ne 0 ] && [ "$status" -ne 125 ]; then
  echo "run-with-xvfb: the command exited with $status on :$display; Xvfb is" \
    "$(kill -0 "$xvfb_pid" 2>/dev/null && echo running || echo gone); its log:" >&2
  cat "$fifo_dir/log" >&2
fi
exit "$status"

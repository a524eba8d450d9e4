#!/usr/bin/env bash
# Run a command under a private Xvfb server: the tests' stand-in for
# xvfb-run. Xvfb picks a free display itself and reports it through
# -displayfd once it accepts connections, so parallel tests and leftover
# lock files cannot race (xvfb-run -a guesses a free number and, under
# load, sometimes hands out a display that refuses the connection).
#   run-with-xvfb.sh COMMAND [ARGS...]
set -euo pipefail
fifo_dir=$(mktemp -d)
trap 'kill "${xvfb_pid:-0}" 2>/dev/null || true; wait "${xvfb_pid:-0}" 2>/dev/null || true; rm -rf "$fifo_dir"' EXIT
mkfifo "$fifo_dir/display"
Xvfb -displayfd 3 -screen 0 1024x768x24 -nolisten tcp 3>"$fifo_dir/display" 2>"$fifo_dir/log" &
xvfb_pid=$!
if ! read -r -t 30 display <"$fifo_dir/display" || [ -z "$display" ]; then
  echo "run-with-xvfb: Xvfb did not start:" >&2
  cat "$fifo_dir/log" >&2
  exit 1
fi
DISPLAY=":$display" "$@"

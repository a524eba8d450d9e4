#!/usr/bin/env bash
# Run a command under a private Xvfb server: the tests' stand-in for
# xvfb-run. The display number is drawn at random from a large range (not
# the first free one: a server on a low number that is shutting down in a
# parallel test can unlink the socket of a new server that just took the
# same number), and the command starts only once Xvfb reports, through
# -displayfd, that it accepts connections. A taken number is retried.
#   run-with-xvfb.sh COMMAND [ARGS...]
set -euo pipefail
fifo_dir=$(mktemp -d)
trap 'kill "${xvfb_pid:-0}" 2>/dev/null || true; wait "${xvfb_pid:-0}" 2>/dev/null || true; rm -rf "$fifo_dir"' EXIT
display=""
for attempt in 1 2 3 4 5 6 7 8; do
  number=$((1000 + RANDOM % 30000))
  rm -f "$fifo_dir/display"
  mkfifo "$fifo_dir/display"
  Xvfb ":$number" -displayfd 3 -screen 0 1024x768x24 -nolisten tcp \
    3>"$fifo_dir/display" 2>"$fifo_dir/log" &
  xvfb_pid=$!
  if read -r -t 30 display <"$fifo_dir/display" && [ -n "$display" ]; then
    break
  fi
  display=""
  kill "$xvfb_pid" 2>/dev/null || true
  wait "$xvfb_pid" 2>/dev/null || true
done
if [ -z "$display" ]; then
  echo "run-with-xvfb: Xvfb did not start:" >&2
  cat "$fifo_dir/log" >&2
  exit 1
fi
DISPLAY=":$display" "$@"

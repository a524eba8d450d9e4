#!/usr/bin/env bash
# Run under Xvfb by test-gui-drag.sh: start the GUI with the startup script,
# find the render view on the screen, drag, wait for the GUI to go idle.
set -uo pipefail
script=$1
events="$CAO_RESULT.events"
now() { date +%s.%N; }
mark() { echo "{\"kind\": \"driver\", \"what\": \"$1\", \"t\": $(now)}" >>"$events"; }
# (CAO_SERVER_URL: connect to that server first: test-gui-remote.sh.)
paraview --dr ${CAO_SERVER_URL:+--server-url="$CAO_SERVER_URL"} --script="$script" >"$CAO_RESULT.gui.log" 2>&1 &
pv=$!
trap 'kill $pv 2>/dev/null; wait $pv 2>/dev/null' EXIT
for _ in $(seq 240); do
  [ -s "$CAO_RESULT.targets" ] && break
  kill -0 $pv 2>/dev/null || { echo "driver: the GUI exited"; tail -20 "$CAO_RESULT.gui.log"; exit 1; }
  if grep -q Traceback "$CAO_RESULT.gui.log"; then
    echo "driver: the startup script failed:"; grep -A8 Traceback "$CAO_RESULT.gui.log"; exit 1
  fi
  sleep 1
done
[ -s "$CAO_RESULT.targets" ] || { echo "driver: no targets after 240 s"; exit 1; }
# Wait for the GUI to draw no more (nothing logged for 3 s and no render
# under way: the last line is not a render's start; at most 120 s; five
# waits and the start fit test-gui-drag.sh's 900 s). A frame longer than
# 3 s (a still frame of embryo.slc on llvmpipe: 5 s) ended the wait while
# it was drawn, and its pose was taken for the next drag's.
idle() {
  local size
  for _ in $(seq 40); do
    size=$(stat -c %s "$events")
    sleep 3
    [ "$(stat -c %s "$events")" = "$size" ] && ! tail -1 "$events" | grep -q '"kind": "start"' && return 0
  done
  echo "driver: the GUI was still drawing after 120 s"
}
idle
# Where is the view? Move over a grid of screen points until the view's
# interactor reports a move, then map its display coordinates to the screen.
read -r width height < <(/usr/bin/python3 -c "import json,sys; t=json.load(open(sys.argv[1])); print(*t['size'])" "$CAO_RESULT.targets")
origin=""
for sy in 450 350 550 250 650; do
  for sx in 650 550 750 450 850; do
    xdotool mousemove $sx $sy
    sleep 0.5
    last=$(grep '"kind": "move"' "$events" | tail -1)
    if [ -n "$last" ]; then
      origin=$(/usr/bin/python3 -c "import json,sys; m=json.loads(sys.argv[1]); print(int(sys.argv[2]) - m['x'], int(sys.argv[3]) + m['y'] - (m['size'][1] - 1))" "$last" $sx $sy)
      break 2
    fi
  done
done
[ -n "$origin" ] || { echo "driver: no mouse move reached the render view"; exit 1; }
read -r ox oy <<<"$origin"
echo "driver: the render view's top-left pixel is at ($ox, $oy) on the screen, ${width}x${height}"
screen() { # display (x, y) of target $1 -> screen x y
  /usr/bin/python3 -c "import json,sys; t=json.load(open(sys.argv[1]))[sys.argv[2]]; print(int(round(t[0])) + $ox, $oy + $height - 1 - int(round(t[1])))" "$CAO_RESULT.targets" "$1"
}
# A user's drag: press, 25 moves 0.1 s apart (2.5 s), release.
drag() { # name x y dx dy [button: 1 left (default), 2 middle]
  local name=$1 x=$2 y=$3 dx=$4 dy=$5 button=${6:-1} k
  xdotool mousemove "$x" "$y"
  sleep 0.5
  mark "$name-press"
  xdotool mousedown "$button"
  for k in $(seq 25); do
    xdotool mousemove $((x + dx * k / 25)) $((y + dy * k / 25))
    sleep 0.1
  done
  xdotool mouseup "$button"
  mark "$name-release"
  idle
  mark "$name-idle"
}
# A first click in an empty corner of the view, as a user's first click
# there: the view takes the keyboard focus (ParaView's first press on a
# view without focus did not reach the widget).
xdotool mousemove $((ox + 20)) $((oy + height - 21)) click 1
sleep 0.5
idle
# The drags the startup script asked for (its targets' "drags": name,
# target, offset x and y in pixels, drag x and y, button), each from that
# target plus its offset.
mapfile -t drags < <(/usr/bin/python3 -c "import json,sys; [print(*d) for d in json.load(open(sys.argv[1]))['drags']]" "$CAO_RESULT.targets")
for line in "${drags[@]}"; do
  read -r name target ox2 oy2 dx dy button <<<"$line"
  read -r x y < <(screen "$target")
  drag "$name" "$((x + ox2))" "$((y + oy2))" "$dx" "$dy" "$button"
done
import -window root "$CAO_RESULT.png" 2>/dev/null || true
exit 0

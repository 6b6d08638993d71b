#!/usr/bin/env bash
# Drags a gizmo's x-arrow with real X events, as a person would: the short
# block's (preselected), or with PICK the gizmo of the object PICK after
# clicking on it (any object can be picked and moved).
# With PICK2 as well, PICK2 is shift+clicked after PICK: both are selected and
# the gizmo (on PICK2) drags them together.
# Run inside one xvfb-run session: drag_gizmo.sh VIEWER SCENE OUTDIR [PICK [PICK2]]
# Writes OUTDIR/{viewer.log,before.png,after.png,undone.png,redone.png,overlays.png} and prints
# "viewer-exit N" last.
set -u
viewer=$1 scene=$2 out=$3 pick=${4:-} pick2=${5:-}
# shot, wait_for, caught_up, settle: on $out/viewer.log and the viewer $pid.
source "$(dirname "$0")/viewer_log.sh"

# A target of 1 fps: each move frame gets a budget for its whole update, so
# that the pictures show the drag and not how far a budget let it get on a
# machine slowed by the sanitizers (budgets are tested in tests/update).
if [ -n "$pick" ]; then
  "$viewer" "$scene" --target-fps 1 --log-transforms --print-gizmo --quit-after 60 >"$out/viewer.log" 2>&1 &
else
  "$viewer" "$scene" --target-fps 1 --select short-block --log-transforms --print-gizmo --quit-after 60 \
    >"$out/viewer.log" 2>&1 &
fi
pid=$!
if [ -n "$pick" ]; then
  wait_for "object: $pick "
  read -r px py < <(awk -v name="$pick" '$1 == "object:" && $2 == name {print $3, $4; exit}' "$out/viewer.log")
  if [ -z "${px:-}" ]; then echo "no object line for $pick"; kill $pid; wait $pid; echo "viewer-exit $?"; exit 1; fi
  sleep 0.5
  xdotool mousemove "$px" "$py"
  sleep 0.3
  xdotool click 1
fi
wait_for "gizmo:"
if [ -n "$pick2" ]; then
  read -r qx qy < <(awk -v name="$pick2" '$1 == "object:" && $2 == name {print $3, $4; exit}' "$out/viewer.log")
  sleep 0.5
  xdotool mousemove "$qx" "$qy"
  sleep 0.3
  # Shift held over a few frames on each side of the click: a slow (sanitizer)
  # frame must not see the click without the shift, nor the shift's release first.
  xdotool keydown shift
  sleep 0.4
  xdotool click 1
  sleep 0.4
  xdotool keyup shift
  # The gizmo moves to the object shift+clicked: its line is the second.
  for _ in $(seq 300); do [ "$(grep -c '^gizmo:' "$out/viewer.log")" -ge 2 ] && break; sleep 0.1; done
fi
read -r x y < <(awk '/^gizmo:/ {x = $3; y = $4} END {print x, y}' "$out/viewer.log")
if [ -z "${x:-}" ]; then echo "no gizmo line"; kill $pid; wait $pid; echo "viewer-exit $?"; exit 1; fi
sleep 0.5
shot "$out/before.png"

# Press on the arrow, move in steps (a drag), release.
moves=$(caught_up)
xdotool mousemove "$x" "$y"
sleep 0.3
xdotool mousedown 1
for i in $(seq 1 12); do
  xdotool mousemove "$((x - 10 * i))" "$y"
  sleep 0.08
done
sleep 0.3
xdotool mouseup 1
xdotool mousemove 1100 60   # off the block and the panel
settle "$moves"
shot "$out/after.png"

# Ctrl+Z takes the drag back, Ctrl+Shift+Z does it again (the preselected
# block's run only: each step waits for the engine).
if [ -z "$pick" ]; then
  moves=$(caught_up)
  xdotool key ctrl+z
  settle "$moves"
  shot "$out/undone.png"
  moves=$(caught_up)
  xdotool key ctrl+shift+z
  settle "$moves"
  shot "$out/redone.png"
fi

xdotool key l
xdotool key c
# The engine thread takes the overlay keys between frames, and on lavapipe
# under load a frame drawing tens of thousands of link lines takes seconds:
# the viewer says when a frame with both overlays has finished.
wait_for "viewer: shown overlays links=1 changed=1"
sleep 0.5
shot "$out/overlays.png"

xdotool key ctrl+q
wait $pid
echo "viewer-exit $?"

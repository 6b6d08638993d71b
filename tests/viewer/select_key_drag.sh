#!/usr/bin/env bash
# Selects SELECT (an object or a light) with --select, presses KEY if given
# (e.g. p: widen the selection), then drags the gizmo's x-arrow with real X
# events, as drag_gizmo.sh does.
# Run inside one xvfb-run session: select_key_drag.sh VIEWER SCENE OUTDIR SELECT [KEY]
# Writes OUTDIR/{viewer.log,before.png,after.png} and prints "viewer-exit N" last.
set -u
viewer=$1 scene=$2 out=$3 select=$4 key=${5:-}
# shot, wait_for, caught_up, settle: on $out/viewer.log and the viewer $pid.
source "$(dirname "$0")/viewer_log.sh"

"$viewer" "$scene" --target-fps 1 --select "$select" --log-transforms --print-gizmo --quit-after 60 \
  >"$out/viewer.log" 2>&1 &
pid=$!
wait_for "gizmo:"
read -r x y < <(awk '/^gizmo:/ {x = $3; y = $4} END {print x, y}' "$out/viewer.log")
if [ -z "${x:-}" ]; then echo "no gizmo line"; kill $pid; wait $pid; echo "viewer-exit $?"; exit 1; fi
sleep 0.5
if [ -n "$key" ]; then
  xdotool mousemove 1100 60   # over the scene, off the panel
  sleep 0.3
  xdotool key "$key"
  sleep 2
fi
shot "$out/before.png"

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
xdotool mousemove 1100 60
settle "$moves"
shot "$out/after.png"

xdotool key ctrl+q
wait $pid
echo "viewer-exit $?"

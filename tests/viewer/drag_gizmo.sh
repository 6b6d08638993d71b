#!/usr/bin/env bash
# Drags the short block's gizmo x-arrow with real X events, as a person would.
# Run inside one xvfb-run session: drag_gizmo.sh VIEWER SCENE OUTDIR
# Writes OUTDIR/{viewer.log,before.png,after.png,overlays.png} and prints
# "viewer-exit N" last.
set -u
viewer=$1 scene=$2 out=$3
shot() { xwd -root -silent -display "$DISPLAY" | convert xwd:- "png:$1"; }

"$viewer" "$scene" --select short-block --log-transforms --print-gizmo --quit-after 60 \
  >"$out/viewer.log" 2>&1 &
pid=$!
for _ in $(seq 300); do
  grep -q '^gizmo:' "$out/viewer.log" && break
  kill -0 $pid 2>/dev/null || break
  sleep 0.1
done
read -r x y < <(awk '/^gizmo:/ {print $3, $4; exit}' "$out/viewer.log")
if [ -z "${x:-}" ]; then echo "no gizmo line"; kill $pid; wait $pid; echo "viewer-exit $?"; exit 1; fi
sleep 0.5
shot "$out/before.png"

# Press on the arrow, move in steps (a drag), release.
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
sleep 2.5
shot "$out/after.png"

xdotool key l
xdotool key c
sleep 1.5
shot "$out/overlays.png"

xdotool key ctrl+q
wait $pid
echo "viewer-exit $?"

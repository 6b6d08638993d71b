# Sourced by the drag scripts: what they read of the viewer's log
# ($out/viewer.log, written by --log-transforms) and its process ($pid).

shot() { xwd -root -silent -display "$DISPLAY" | convert xwd:- "png:$1"; }
# Waits (up to 30 s) for a line of the log starting with $1.
wait_for() {
  for _ in $(seq 300); do
    grep -q "^$1" "$out/viewer.log" && return 0
    kill -0 $pid 2>/dev/null || return 1
    sleep 0.1
  done
  return 1
}
# The moves the engine had taken when its last line said it caught up, or -1
# while it is still at work.
caught_up() {
  awk '/^engine: / {last = $0} END {if (last ~ /^engine: caught up after /) {split(last, w, " "); print w[5]} else print -1}' \
    "$out/viewer.log"
}
# Waits (up to 60 s) until the engine has taken more moves than $1 and has
# nothing left to update (what budgets left stale or coarse takes seconds
# under the sanitizers), and a frame showing that has finished.
settle() {
  for _ in $(seq 600); do
    local m
    m=$(caught_up)
    [ "$m" -gt "$1" ] && grep -q "^viewer: shown caught up after $m moves" "$out/viewer.log" && { sleep 0.3; return 0; }
    kill -0 $pid 2>/dev/null || return 1
    sleep 0.1
  done
  return 1
}

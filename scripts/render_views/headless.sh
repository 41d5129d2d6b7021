# Sourced by scripts/render and scripts/replay.
# headless WIDTH HEIGHT LOG CMD...: runs CMD with DISPLAY on a private Xvfb server, its output
# appended to LOG. The server picks a free display itself and says which once it accepts
# connections (-displayfd), so renders started together never share or miss one (xvfb-run -a
# picks the number before its server starts, and once all three tries of a render failed with
# "bad X server connection"). -noreset: by default the server resets when its last client
# leaves, and a client connecting meanwhile is cut off; pvbatch closes one connection before it
# opens the next, so on a loaded machine 4 in 6 renders failed with "bad X server connection".
headless() {
  local width=$1 height=$2 log=$3
  shift 3
  local dir pid display rc=0
  dir=$(mktemp -d)
  Xvfb -displayfd 1 -screen 0 "${width}x${height}x24" -nolisten tcp -noreset >"$dir/display" 2>>"$log" &
  pid=$!
  for _ in $(seq 300); do  # up to 30 s for the server to start
    [ -s "$dir/display" ] && break
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
  done
  display=$(head -n 1 "$dir/display" 2>/dev/null || true)
  if [[ "$display" =~ ^[0-9]+$ ]]; then
    DISPLAY=:$display "$@" >>"$log" 2>&1 || rc=$?
  else
    echo "# Xvfb did not start" >>"$log"
    rc=1
  fi
  kill "$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null || true
  rm -rf "$dir"
  return $rc
}

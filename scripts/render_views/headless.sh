# Sourced by scripts/render and scripts/replay.
# headless WIDTH HEIGHT LOG CMD...: runs CMD with DISPLAY on a private Xvfb server, its output
# appended to LOG. The server takes the first free display from :10 up and says so once it
# accepts connections (-displayfd), so renders started together never share or miss one (xvfb-run
# -a picks the number before its server starts, and once all three tries of a render failed with
# "bad X server connection"). Not :0-:9: every MPI program started meanwhile probes those for GPUs
# (hwloc's GL plugin) and dies with "X connection to :0 broken" when the server it found goes
# away, which once failed an unrelated test run beside a render. -noreset: by default the server
# resets when its last client leaves, and a client connecting meanwhile is cut off; pvbatch closes
# one connection before it opens the next, so on a loaded machine 4 in 6 renders failed with
# "bad X server connection".
headless() {
  local width=$1 height=$2 log=$3
  shift 3
  local dir pid display rc=0
  dir=$(mktemp -d)
  local n
  for n in $(seq 10 99); do
    # A display in use (its lock held) makes the server exit at once: try the next. Only the
    # server that started has its lines kept in LOG.
    [ -e "/tmp/.X$n-lock" ] && continue
    Xvfb ":$n" -displayfd 1 -screen 0 "${width}x${height}x24" -nolisten tcp -noreset \
      >"$dir/display" 2>"$dir/server" &
    pid=$!
    for _ in $(seq 300); do  # up to 30 s for the server to start
      [ -s "$dir/display" ] && break
      kill -0 "$pid" 2>/dev/null || break
      sleep 0.1
    done
    [ -s "$dir/display" ] && break
    wait "$pid" 2>/dev/null || true
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
  cat "$dir/server" >>"$log" 2>/dev/null || true
  rm -rf "$dir"
  return $rc
}

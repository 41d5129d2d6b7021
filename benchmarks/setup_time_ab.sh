#!/usr/bin/env bash
# Set-up time of two builds side by side: one process runs SCENE for one step (set-up, the
# first frame and the step), build A and B in turn, ROUNDS rounds, the one that runs first
# alternating. Prints each run's wall time and peak RSS, then the median over rounds of the
# ratio A / B (the figure to quote) with its min-max.
# usage: benchmarks/setup_time_ab.sh ROUNDS EXE_A EXE_B SCENE [--preset P] [--set key=value]...
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -ge 4 ] || { echo "usage: benchmarks/setup_time_ab.sh ROUNDS EXE_A EXE_B SCENE [--preset P] [--set key=value]..." >&2; exit 2; }
rounds=$1 exe_a=$2 exe_b=$3
shift 3
. benchmarks/common.sh
echo "# setup_time_ab.sh: $*, one step; A $exe_a, B $exe_b; $rounds rounds; $(date -u +%FT%TZ); $(nproc) cores,$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"
commit_line
for r in $(seq 1 "$rounds"); do
  order="a b"; [ $((r % 2)) = 0 ] && order="b a"
  for w in $order; do
    exe_w=$exe_a; [ "$w" = b ] && exe_w=$exe_b
    rm -rf "$work/o"
    /usr/bin/time -o "$work/time" -f "%e %M" "$exe_w" run "$@" --set steps=1 --set progress_interval=0 \
      -o "$work/o" >"$work/out" 2>&1 || { echo "setup_time_ab: build $w failed:" >&2; cat "$work/out" >&2; exit 1; }
    read -r secs rss <"$work/time"
    echo "round $r $w $secs s, peak RSS $rss KB, $(grep -o ' N=[0-9]*' "$work/out" | head -1)"
    echo "$secs" >"$work/$w"
  done
  awk -v a="$(cat "$work/a")" -v b="$(cat "$work/b")" 'BEGIN {print a / b}' >>"$work/ratios"
done
echo "A / B wall time: median $(median <"$work/ratios"), min $(sort -g "$work/ratios" | head -1), max $(sort -g "$work/ratios" | tail -1) over $rounds rounds"

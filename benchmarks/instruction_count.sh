#!/usr/bin/env bash
# Instructions (and with CACHE=yes, cache misses) per step of several builds on one state, under
# valgrind's cachegrind: where perf has no hardware counters (a virtual machine), the count of what
# each build executes, free of the machine's load. The first build settles the scene's `small`
# preset 100 steps on 2 ranks; each build continues that checkpoint for S1 and for S2 steps; per
# step = (S2 count - S1 count) / (S2 - S1), summed over the ranks, for all instructions and for
# the engine's alone (the MPI library's progress and waiting loops left out: their counts follow
# how long a rank waits, not what it computes). CACHE=yes adds the first-level data-cache read
# misses per step. Slow: ~50x a plain run.
# usage: benchmarks/instruction_count.sh SCENE S1 S2 EXE... [-- SCENE_SETTINGS...]
set -euo pipefail
cd "$(dirname "$0")/.."
scene=$1 s1=$2 s2=$3
shift 3
exes=()
while [ $# -gt 0 ] && [ "$1" != -- ]; do exes+=("$1"); shift; done
[ "${1:-}" = -- ] && shift
. benchmarks/common.sh
settle_checkpoint "${exes[0]}" 2 100 "$scene" --preset small "$@"
engine_work() {  # the instructions of one cachegrind file outside the MPI library
  cg_annotate --auto=no --threshold=0 "$1" | sed -n '/Ir.*file:function/,$p' | awk 'NR > 2 {
    gsub(",", "", $1); if ($0 !~ /\?\?\?:\?\?\?|opal_|ompi_|NBC_|libnbc|mca_/) w += $1 } END {printf "%.0f\n", w}'
}
for k in "${!exes[@]}"; do
  for s in $s1 $s2; do
    rm -rf "$work/t"
    mpirun -q --oversubscribe -np 2 valgrind --tool=cachegrind --cache-sim="${CACHE:-no}" \
      --cachegrind-out-file="$work/cg.$k.$s.%q{OMPI_COMM_WORLD_RANK}" "${exes[$k]}" run \
      --restart "$work/settle/checkpoint.h5" --set steps=$((100 + s)) --set checkpoint_every=0 \
      --set progress_interval=0 -o "$work/t" >/dev/null 2>"$work/valgrind.err"
  done
  all=() work_=() miss=()
  for s in $s1 $s2; do
    all+=("$(grep -h '^summary:' "$work"/cg.$k.$s.* | awk '{s += $2} END {printf "%.0f", s}')")
    miss+=("$(grep -h '^summary:' "$work"/cg.$k.$s.* | awk '{s += $6} END {printf "%.0f", s}')")
    work_+=("$(for f in "$work"/cg.$k.$s.*; do engine_work "$f"; done | awk '{s += $1} END {printf "%.0f", s}')")
  done
  per() { awk -v a="$1" -v b="$2" -v d=$((s2 - s1)) 'BEGIN {printf "%.4g", (b - a) / d}'; }
  line="${exes[$k]}: per step, all instructions $(per "${all[@]}"), the engine's $(per "${work_[@]}")"
  [ "${CACHE:-no}" = yes ] && line+=", D1 read misses $(per "${miss[@]}")"
  echo "$line"
done

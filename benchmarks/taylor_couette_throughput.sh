#!/usr/bin/env bash
# Throughput of the taylor-couette `small` preset (the paper's small system: quadrant of
# r_i=50, d=25, L=100, ~1.2e5 WCA atoms, thermal walls, rotational images): 200 warm-up steps,
# then 3000 timed steps, on each rank count, REPEATS runs interleaved; medians. Field
# coarse-graining as in the preset (a sample every 10 steps) is included. The preset starts
# with its hold at omega 0.07; further arguments go to the scene, e.g. --set spin_up_time=0 for
# the rate at omega 0.1 (a faster wall ages the lists sooner).
# usage: benchmarks/taylor_couette_throughput.sh [REPEATS] [RANKS] [SCENE_ARGS...]
#        (defaults 3, "1 2")
set -euo pipefail
cd "$(dirname "$0")/.."
repeats=${1:-3}
ranks_list=${2:-"1 2"}
shift $(( $# < 2 ? $# : 2 ))
. benchmarks/common.sh
for r in $(seq "$repeats"); do
  for np in $ranks_list; do
    mpirun -q --oversubscribe -np "$np" "$exe" run taylor-couette --preset small \
      --set equilibration_steps=200 --set steps=3000 --set progress_interval=0 \
      -o "$work/run" --overwrite --summary-json "$work/s.json" "$@" >/dev/null
    grep -o '"atom_steps_per_second": [0-9.e+]*' "$work/s.json" | awk '{print $2}' >>"$work/r$np"
    grep -o '"bytes_per_particle": [0-9.e+]*' "$work/s.json" | awk '{print $2}' >>"$work/m$np"
    grep -o '"N": [0-9]*' "$work/s.json" | awk '{print $2}' >"$work/n"
  done
done
printf '| ranks | atom-steps/s (N=%s) | steps/s | B/atom |\n|---|---|---|---|\n' "$(cat "$work/n")"
for np in $ranks_list; do
  rate=$(median <"$work/r$np")
  printf '| %d | %.3g | %.0f | %.0f |\n' "$np" "$rate" "$(echo "$rate / $(cat "$work/n")" | bc -l)" \
    "$(median <"$work/m$np")"
done

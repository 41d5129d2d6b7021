#!/usr/bin/env bash
# rotating-drum throughput: the `small` preset's drum (D = 50, L = 24, 2608 tetrahedra =
# 10432 spheres, fill ~0.3) turned for one revolution (6300 steps, settled and rolling), then
# 3150 steps (half a revolution) timed on 1 and 2 ranks, REPEATS alternating runs. Rates count
# sphere-steps (constituent spheres; the wall spheres are not particles).
# usage: benchmarks/rotating_drum.sh [REPEATS] [RANKS]    (defaults 3, "1 2")
set -euo pipefail
cd "$(dirname "$0")/.."
repeats=${1:-3}
ranks_list=${2:-"1 2"}
. benchmarks/common.sh
"$exe" run rotating-drum --preset small --set steps=6300 --set checkpoint_every=6300 \
  --set output.every=0 --set progress_interval=0 -o "$work/turn" >/dev/null
printf '| ranks | sphere-steps/s (10432 spheres in 2608 tetrahedra) | B/sphere |\n|---|---|---|\n'
for np in $ranks_list; do : >"$work/r$np"; : >"$work/m$np"; done
for r in $(seq "$repeats"); do
  for np in $ranks_list; do
    mpirun --oversubscribe -np "$np" "$exe" run --restart "$work/turn/checkpoint.h5" \
      --set steps=9450 --set checkpoint_every=0 --set progress_interval=0 \
      --summary-json "$work/s.json" >/dev/null
    grep -o '"atom_steps_per_second": [0-9.e+]*' "$work/s.json" | awk '{print $2}' >>"$work/r$np"
    grep -o '"bytes_per_particle": [0-9.e+]*' "$work/s.json" | awk '{print $2}' >>"$work/m$np"
  done
done
for np in $ranks_list; do
  printf '| %d | %.3g | %.0f |\n' "$np" "$(median <"$work/r$np")" "$(median <"$work/m$np")"
done

#!/usr/bin/env bash
# rotating-drum throughput: the `small` preset's drum (D = 50, L = 24, 2592 tetrahedra =
# 10368 spheres, fill 0.25) turned for one revolution (6300 steps, settled and rolling), then
# 3150 steps (half a revolution) timed; REPEATS alternating runs of each case. First the
# neighbour skin on 1 rank (benchmarks/skin_sweep.sh; the whole bed turns, so lists age fast:
# the skin sets how often they are rebuilt), then 1 and 2 ranks at the scene's default skin.
# Rates count sphere-steps (constituent spheres; the wall spheres are not particles).
# usage: benchmarks/rotating_drum.sh [REPEATS] [RANKS] [SKINS]    (defaults 3, "1 2", "0.3 0.5 0.7 1.0")
set -euo pipefail
cd "$(dirname "$0")/.."
repeats=${1:-3}
ranks_list=${2:-"1 2"}
skins=${3:-"0.3 0.5 0.7 1.0"}
. benchmarks/common.sh
"$exe" run rotating-drum --preset small --set steps=6300 --set checkpoint_every=6300 \
  --set output.every=0 --set progress_interval=0 -o "$work/turn" >/dev/null
benchmarks/skin_sweep.sh 1 6300 3150 "$repeats" "$skins" rotating-drum --preset small
for r in $(seq "$repeats"); do
  for np in $ranks_list; do
    mpirun --oversubscribe -np "$np" "$exe" run --restart "$work/turn/checkpoint.h5" \
      --set steps=9450 --set checkpoint_every=0 --set progress_interval=0 \
      -o "$work/timed" --overwrite --summary-json "$work/s.json" >/dev/null
    grep -o '"atom_steps_per_second": [0-9.e+]*' "$work/s.json" | awk '{print $2}' >>"$work/r$np"
    grep -o '"bytes_per_particle": [0-9.e+]*' "$work/s.json" | awk '{print $2}' >>"$work/m$np"
  done
done
printf '\n| ranks (default skin) | sphere-steps/s | B/sphere |\n|---|---|---|\n'
for np in $ranks_list; do
  printf '| %d | %.3g | %.0f |\n' "$np" "$(median <"$work/r$np")" "$(median <"$work/m$np")"
done

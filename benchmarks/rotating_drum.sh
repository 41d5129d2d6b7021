#!/usr/bin/env bash
# rotating-drum throughput: the `small` preset's drum (D = 50, L = 24, 2592 tetrahedra =
# 10368 spheres, fill 0.25) turned for one revolution (6300 steps, settled and rolling), then
# 3150 steps (half a revolution) timed; REPEATS alternating runs of each case. First the
# neighbour skin on 1 rank (the whole bed turns, so lists age fast: the skin sets how often
# they are rebuilt), then 1 and 2 ranks at the scene's default skin. Rates count sphere-steps
# (constituent spheres; the wall spheres are not particles).
# usage: benchmarks/rotating_drum.sh [REPEATS] [RANKS] [SKINS]    (defaults 3, "1 2", "0.3 0.5 0.7 1.0")
set -euo pipefail
cd "$(dirname "$0")/.."
repeats=${1:-3}
ranks_list=${2:-"1 2"}
skins=${3:-"0.3 0.5 0.7 1.0"}
. benchmarks/common.sh
"$exe" run rotating-drum --preset small --set steps=6300 --set checkpoint_every=6300 \
  --set output.every=0 --set progress_interval=0 -o "$work/turn" >/dev/null
rebuilds0=$(grep -o '"neighbour_rebuilds": [0-9]*' "$work/turn/summary.json" | awk '{print $2}')
timed() {  # ranks, extra args...; appends rate, memory and list builds to files named by $tag
  local np=$1; shift
  mpirun --oversubscribe -np "$np" "$exe" run --restart "$work/turn/checkpoint.h5" \
    --set steps=9450 --set checkpoint_every=0 --set progress_interval=0 "$@" \
    --summary-json "$work/s.json" >/dev/null
  grep -o '"atom_steps_per_second": [0-9.e+]*' "$work/s.json" | awk '{print $2}' >>"$work/r$tag"
  grep -o '"bytes_per_particle": [0-9.e+]*' "$work/s.json" | awk '{print $2}' >>"$work/m$tag"
  grep -o '"neighbour_rebuilds": [0-9]*' "$work/s.json" | awk -v r0="$rebuilds0" '{print $2 - r0}' >>"$work/b$tag"
}
for r in $(seq "$repeats"); do
  for sk in $skins; do tag=skin$sk; timed 1 --set skin="$sk"; done
  for np in $ranks_list; do tag=np$np; timed "$np"; done
done
printf '| skin (1 rank) | sphere-steps/s | list builds in 3150 steps | B/sphere |\n|---|---|---|---|\n'
for sk in $skins; do
  printf '| %s | %.3g | %.0f | %.0f |\n' "$sk" "$(median <"$work/rskin$sk")" \
    "$(median <"$work/bskin$sk")" "$(median <"$work/mskin$sk")"
done
printf '\n| ranks (default skin) | sphere-steps/s | B/sphere |\n|---|---|---|\n'
for np in $ranks_list; do
  printf '| %d | %.3g | %.0f |\n' "$np" "$(median <"$work/rnp$np")" "$(median <"$work/mnp$np")"
done

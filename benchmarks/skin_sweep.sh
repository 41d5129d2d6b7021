#!/usr/bin/env bash
# Throughput of a scene against the neighbour-list skin: the scene runs SETTLE steps once (past
# its start-up) and leaves a checkpoint; each skin then continues it for TIMED steps, REPEATS
# rounds alternating over the skins. Reports the median rate (particle-steps/s), list builds in
# the timed steps and memory. A larger skin means fewer list builds but longer lists: where the
# optimum lies depends on how fast particles move (hot walls, turning beds).
# usage: benchmarks/skin_sweep.sh RANKS SETTLE TIMED REPEATS "SKINS" SCENE [--set key=value]...
set -euo pipefail
cd "$(dirname "$0")/.."
ranks=$1 settle=$2 timed_steps=$3 repeats=$4 skins=$5 scene=$6
shift 6
. benchmarks/common.sh
mpirun --oversubscribe -np "$ranks" "$exe" run "$scene" "$@" --set steps="$settle" \
  --set equilibration_steps=0 --set checkpoint_every="$settle" --set output.every=0 \
  --set progress_interval=0 -o "$work/settle" >/dev/null
rebuilds0=$(grep -o '"neighbour_rebuilds": [0-9]*' "$work/settle/summary.json" | awk '{print $2}')
for r in $(seq "$repeats"); do
  for sk in $skins; do
    mpirun --oversubscribe -np "$ranks" "$exe" run --restart "$work/settle/checkpoint.h5" \
      --set steps=$((settle + timed_steps)) --set checkpoint_every=0 --set progress_interval=0 \
      --set skin="$sk" --summary-json "$work/s.json" >/dev/null
    grep -o '"atom_steps_per_second": [0-9.e+]*' "$work/s.json" | awk '{print $2}' >>"$work/r$sk"
    grep -o '"bytes_per_particle": [0-9.e+]*' "$work/s.json" | awk '{print $2}' >>"$work/m$sk"
    grep -o '"neighbour_rebuilds": [0-9]*' "$work/s.json" | awk -v r0="$rebuilds0" '{print $2 - r0}' >>"$work/b$sk"
  done
done
printf '| skin (%d ranks) | particle-steps/s | list builds in %d steps | B/particle |\n|---|---|---|---|\n' \
  "$ranks" "$timed_steps"
for sk in $skins; do
  printf '| %s | %.3g | %.0f | %.0f |\n' "$sk" "$(median <"$work/r$sk")" "$(median <"$work/b$sk")" \
    "$(median <"$work/m$sk")"
done

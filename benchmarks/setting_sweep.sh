#!/usr/bin/env bash
# Throughput of a scene against one run setting (skin, cell_subdivisions, ...): the scene runs
# SETTLE steps once (past its start-up) and leaves a checkpoint; each value then continues it
# for TIMED steps, REPEATS rounds alternating over the values, so the machine's load drifts
# alike over all of them. Reports the median rate (particle-steps/s), list builds in the timed
# steps and peak memory.
# usage: benchmarks/setting_sweep.sh RANKS SETTLE TIMED REPEATS KEY "VALUES" SCENE [--set key=value]...
set -euo pipefail
cd "$(dirname "$0")/.."
ranks=$1 settle=$2 timed_steps=$3 repeats=$4 key=$5 values=$6 scene=$7
shift 7
. benchmarks/common.sh
mpirun --oversubscribe -np "$ranks" "$exe" run "$scene" "$@" --set steps="$settle" \
  --set equilibration_steps=0 --set checkpoint_every="$settle" --set output.every=0 \
  --set progress_interval=0 -o "$work/settle" >/dev/null
rebuilds0=$(grep -o '"neighbour_rebuilds": [0-9]*' "$work/settle/summary.json" | awk '{print $2}')
for r in $(seq "$repeats"); do
  for v in $values; do
    mpirun --oversubscribe -np "$ranks" "$exe" run --restart "$work/settle/checkpoint.h5" \
      --set steps=$((settle + timed_steps)) --set checkpoint_every=0 --set progress_interval=0 \
      --set "$key=$v" --summary-json "$work/s.json" >/dev/null
    grep -o '"atom_steps_per_second": [0-9.e+]*' "$work/s.json" | awk '{print $2}' >>"$work/r$v"
    grep -o '"bytes_per_particle": [0-9.e+]*' "$work/s.json" | awk '{print $2}' >>"$work/m$v"
    grep -o '"neighbour_rebuilds": [0-9]*' "$work/s.json" | awk -v r0="$rebuilds0" '{print $2 - r0}' >>"$work/b$v"
  done
done
printf '| %s (%d ranks) | particle-steps/s | list builds in %d steps | B/particle |\n|---|---|---|---|\n' \
  "$key" "$ranks" "$timed_steps"
for v in $values; do
  printf '| %s | %.3g | %.0f | %.0f |\n' "$v" "$(median <"$work/r$v")" "$(median <"$work/b$v")" \
    "$(median <"$work/m$v")"
done

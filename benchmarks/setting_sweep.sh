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
settle_checkpoint "$exe" "$ranks" "$settle" "$scene" "$@"
rebuilds0=$(summary_value "$work/settle/summary.json" neighbour_rebuilds)
for r in $(seq "$repeats"); do
  for v in $values; do
    mpirun --oversubscribe -np "$ranks" "$exe" run --restart "$work/settle/checkpoint.h5" \
      --set steps=$((settle + timed_steps)) --set checkpoint_every=0 --set progress_interval=0 \
      --set "$key=$v" -o "$work/timed" --overwrite --summary-json "$work/s.json" >/dev/null
    summary_value "$work/s.json" atom_steps_per_second >>"$work/r$v"
    summary_value "$work/s.json" bytes_per_particle >>"$work/m$v"
    echo $(( $(summary_value "$work/s.json" neighbour_rebuilds) - rebuilds0 )) >>"$work/b$v"
  done
done
printf '| %s (%d ranks) | particle-steps/s | list builds in %d steps | B/particle |\n|---|---|---|---|\n' \
  "$key" "$ranks" "$timed_steps"
for v in $values; do
  printf '| %s | %.3g | %.0f | %.0f |\n' "$v" "$(median <"$work/r$v")" "$(median <"$work/b$v")" \
    "$(median <"$work/m$v")"
done

#!/usr/bin/env bash
# Cost of the run-time guards when nothing is wrong: the bench preset (WCA, N = 32000, NVE)
# with the default guards (every 100 steps) against guards off, alternating, REPEATS each.
# usage: benchmarks/guard_cost.sh [REPEATS]
set -euo pipefail
cd "$(dirname "$0")/.."
exe=$PWD/build/bin/emergent
repeats=${1:-5}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
median() { sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
for r in $(seq "$repeats"); do
  for mode in on off; do
    extra=()
    [ $mode = off ] && extra=(--set guard.every=0 --set guard.max_energy_drift=0 --set guard.max_force=0)
    "$exe" run lj-fluid --preset bench --set progress_interval=0 "${extra[@]}" \
      --summary-json "$tmp/$mode.json" >/dev/null
    grep -o '"atom_steps_per_second": [0-9.e+]*' "$tmp/$mode.json" | awk '{print $2}' >>"$tmp/$mode"
  done
done
on=$(median <"$tmp/on"); off=$(median <"$tmp/off")
echo "guards on: $on atom-steps/s, off: $off atom-steps/s, on/off = $(awk -v a="$on" -v b="$off" 'BEGIN {printf "%.3f", a/b}') (median of $repeats alternating runs)"

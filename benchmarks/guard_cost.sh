#!/usr/bin/env bash
# Cost of the run-time guards when nothing is wrong (WCA, rho = 0.8, NVE, default guards: a
# state check every 100 steps plus a snapshot of the last good state) against guards off.
# Wall time on a shared 2-core machine is too noisy for a percent-level difference, so the
# primary figure is the instruction count under valgrind's callgrind (exact and repeatable);
# the median wall-clock ratio of alternating runs is printed beside it.
# usage: benchmarks/guard_cost.sh [REPEATS]
set -euo pipefail
cd "$(dirname "$0")/.."
exe=$PWD/build/bin/emergent
repeats=${1:-5}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
median() { sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
off=(--set guard.every=0 --set guard.max_energy_drift=0 --set guard.max_force=0)
for mode in on off; do
  extra=(); [ $mode = off ] && extra=("${off[@]}")
  valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.$mode" "$exe" run lj-fluid --preset bench \
    --set n_cells=8 --set equilibration_steps=0 --set steps=1000 --set progress_interval=0 \
    "${extra[@]}" 2>"$tmp/vg.$mode" >/dev/null
  grep -o 'Collected : [0-9]*' "$tmp/vg.$mode" | awk '{print $3}' >"$tmp/ir.$mode"
done
echo "instructions (N = 2048, 1000 steps): guards on $(cat "$tmp/ir.on"), off $(cat "$tmp/ir.off"), on/off = $(awk -v a="$(cat "$tmp/ir.on")" -v b="$(cat "$tmp/ir.off")" 'BEGIN {printf "%.4f", a/b}')"
for r in $(seq "$repeats"); do
  for mode in off on; do  # alternate, starting with 'off' (order effects show up as noise)
    extra=(); [ $mode = off ] && extra=("${off[@]}")
    "$exe" run lj-fluid --preset bench --set progress_interval=0 "${extra[@]}" \
      --summary-json "$tmp/$mode.json" >/dev/null
    grep -o '"atom_steps_per_second": [0-9.e+]*' "$tmp/$mode.json" | awk '{print $2}' >>"$tmp/$mode"
  done
done
on=$(median <"$tmp/on"); off_rate=$(median <"$tmp/off")
echo "wall clock (N = 32000): guards on $on, off $off_rate atom-steps/s, on/off = $(awk -v a="$on" -v b="$off_rate" 'BEGIN {printf "%.3f", a/b}') (median of $repeats alternating runs)"

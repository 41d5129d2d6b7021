#!/usr/bin/env bash
# Work-precision of lj-fluid: wall time per unit of simulated time against the errors of each
# time step, skin and integrator (velocity Verlet, Omelyan's minimum-error splitting), for WCA
# at rho = 0.8, T = 1 and a dense/hot state (rho = 1.0, T = 2).
#
# Each case starts from the same equilibrated state (a checkpoint) and runs NVE for 10 tau; a
# velocity-Verlet run at dt = 0.0005 is the reference. Errors: energy drift rate and fluctuation per particle,
# mean P and U against the reference (with block standard errors), and the short-time
# trajectory error (RMS position difference from the reference after 0.5 tau).
# Writes a Markdown table to stdout and a PNG diagram (scripts/work_precision_report).
#
# usage: benchmarks/work_precision.sh [OUT_DIR] [REPEATS]    (default /tmp/emergent_wp, 3; OUT_DIR
#        is emptied first: it must be empty or this script's earlier output)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-/tmp/emergent_wp}
repeats=${2:-3}
exe=$PWD/build/bin/emergent
if [ -n "$(ls -A "$out" 2>/dev/null)" ] && [ ! -d "$out/wca/base" ]; then
  echo "work_precision.sh: $out holds other files than this script's earlier output, and would be emptied: choose another OUT_DIR" >&2
  exit 2
fi
rm -rf "$out" && mkdir -p "$out"
tau=10
case_args() {  # name -> scene settings
  case $1 in
    wca) echo "--set density=0.8 --set temperature=1" ;;
    dense_hot) echo "--set density=1.0 --set temperature=2" ;;
  esac
}
for state in wca dense_hot; do
  base=$out/$state/base
  # shellcheck disable=SC2046
  "$exe" run lj-fluid --set n_cells=10 $(case_args $state) --set equilibration_steps=4000 \
    --set steps=0 --set progress_interval=0 --checkpoint-every 4000 -o "$base" >/dev/null
  run_case() {  # label dt skin repeat [integrator]
    local dir=$out/$state/$1/r$4 steps every
    mkdir -p "$(dirname "$dir")"
    steps=$(awk -v dt="$2" -v t=$tau 'BEGIN { printf "%d", t / dt + 0.5 }')
    every=$(awk -v dt="$2" 'BEGIN { printf "%d", 0.5 / dt + 0.5 }')
    # A case that goes unstable stops with its guard's message; it is reported, not fatal.
    "$exe" run --restart "$base/checkpoint.h5" --set thermostat=none --set dt="$2" --set skin="$3" \
      --set integrator="${5:-verlet}" \
      --set steps="$steps" --set sample_every="$every" --set output.every="$every" \
      --set output.elements=position,image --set checkpoint_every=0 \
      --summary-json "$dir.json" -o "$dir" >/dev/null 2>"$dir.err" || { cat "$dir.err" >&2; rm -f "$dir.json"; }
  }
  run_case ref 0.0005 0.3 1
  for r in $(seq "$repeats"); do
    # Steps per 0.5 tau must be whole and divide the checkpoint step (4000), so that every
    # run has a frame at exactly 0.5 tau for the trajectory error.
    for dt in 0.001 0.002 0.0025 0.004 0.005 0.00625 0.01; do run_case "dt${dt}_skin0.3" "$dt" 0.3 "$r"; done
    for skin in 0.2 0.4 0.6; do run_case "dt0.005_skin$skin" 0.005 "$skin" "$r"; done
    # Two force evaluations per step: compare at twice velocity Verlet's dt for equal cost.
    for dt in 0.0025 0.004 0.005 0.00625 0.01 0.0125; do
      run_case "dt${dt}_skin0.3_omelyan" "$dt" 0.3 "$r" omelyan
    done
  done
done
/usr/bin/python3 scripts/work_precision_report "$out" "$out/work_precision.png"

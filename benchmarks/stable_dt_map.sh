#!/usr/bin/env bash
# Largest stable time step of the WCA fluid (rho = 0.8) against temperature.
# A step counts as stable when an NVE run of 10 tau from the fcc lattice (N = 500) finishes
# with |E(t) - E(0)| per particle below 0.01 T at every sample (guard.max_energy_drift: 1 % of
# the thermal energy scale, so the criterion means the same at every T) and no
# other guard fires. Prints a Markdown table.
# usage: benchmarks/stable_dt_map.sh
set -euo pipefail
cd "$(dirname "$0")/.."
exe=$PWD/build/bin/emergent
dts="0.0005 0.001 0.002 0.003 0.004 0.005 0.006 0.008 0.01 0.012 0.015 0.02"
printf '| T | largest stable dt (of %s) | first failing dt: reason |\n|---|---|---|\n' "${dts// /, }"
for T in 0.5 1 2 5 10 20 50 100; do
  best="none"; fail="-"
  for dt in $dts; do
    steps=$(awk -v dt="$dt" 'BEGIN { printf "%d", 10 / dt + 0.5 }')
    if msg=$("$exe" run lj-fluid --set n_cells=5 --set temperature="$T" --set thermostat=none \
          --set dt="$dt" --set equilibration_steps=0 --set steps="$steps" --set sample_every=20 \
          --set guard.max_energy_drift="$(awk -v t="$T" 'BEGIN {print 0.01 * t}')" \
          --set guard.every=20 --set progress_interval=0 \
          2>&1 >/dev/null); then
      best=$dt
    else
      fail="$dt: $(sed -e 's/^emergent: run stopped: //' -e 's/;.*//' <<<"$msg" | cut -c1-70)"
      break
    fi
  done
  printf '| %s | %s | %s |\n' "$T" "$best" "$fail"
done

#!/usr/bin/env bash
# The progress line of a continued run gives the rate of the steps it ran, not of all steps
# since step 0 (which once showed a run continued from step 30000 as ~30x faster than it was).
# usage: progress_rate_after_restart.sh EMERGENT
set -euo pipefail
exe=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$exe" run lj-fluid --preset tiny --set equilibration_steps=0 --set steps=30000 \
  --set sample_every=1000 --set progress_interval=0 --set checkpoint_every=30000 -o "$dir/first" >/dev/null
# 1000 further steps, a progress line at every sample.
"$exe" run --restart "$dir/first/checkpoint.h5" --set steps=31000 --set checkpoint_every=0 \
  --set sample_every=20 --set progress_interval=1e-9 --summary-json "$dir/s.json" >"$dir/out"
shown=$(grep -o '[0-9.e+]* steps/s' "$dir/out" | tail -n 1 | awk '{print $1}')
wall=$(grep -o '"wall_seconds": [0-9.e+-]*' "$dir/s.json" | awk '{print $2}')
[ -n "$shown" ] && [ -n "$wall" ] || { echo "FAIL: no progress line or no wall time"; exit 1; }
# The last line (step 31000) should show ~1000 / wall steps/s; counting from step 0 gives 31x
# that. A factor 3 leaves room for the few steps and the start-up the two clocks differ by.
awk -v shown="$shown" -v wall="$wall" 'BEGIN {
  real = 1000 / wall
  if (shown > 3 * real) { printf "FAIL: progress shows %g steps/s, the run made %g\n", shown, real; exit 1 }
  printf "ok: progress shows %g steps/s, the run made %g\n", shown, real }'

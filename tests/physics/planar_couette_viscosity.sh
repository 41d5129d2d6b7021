#!/usr/bin/env bash
# The shear viscosity planar-couette measures (its default settings: lattice density 0.488 between
# thermal walls at T = 1 moving at +-1.5, 20.3 apart) against an independent value at the state
# the run reaches in mid-channel (rho 0.465, T 1.27, viscous heating included): see
# tests/physics/planar_couette_viscosity.py for the reference, its uncertainty and the tolerance.
# STEPS measured steps (frames of 5000: block errors from 10 blocks of them), on NP ranks.
# usage: planar_couette_viscosity.sh EMERGENT MPIRUN NP STEPS
set -euo pipefail
exe=$1
mpirun=$2
np=$3
steps=$4
here=$(cd "$(dirname "$0")" && pwd)
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
rc=0
"$mpirun" -q --allow-run-as-root --oversubscribe -np "$np" "$exe" run planar-couette \
  --set equilibration_steps=20000 --set steps="$steps" --set sample_every=10000 \
  --set fields.interval=5000 --set progress_interval=0 --set output.snapshot_seconds=0 \
  -o "$dir/run" >"$dir/log" 2>&1 || rc=$?
[ $rc = 0 ] || { echo "FAIL: planar-couette on $np rank(s) exited with status $rc:"; tail -5 "$dir/log"; exit 1; }
/usr/bin/python3 "$here/planar_couette_viscosity.py" "$dir/run/summary.json"

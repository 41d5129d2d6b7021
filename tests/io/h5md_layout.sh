#!/usr/bin/env bash
# Writes trajectories on 1 and 4 ranks and checks them with check_h5md.py.
# usage: h5md_layout.sh EMERGENT MPIRUN
set -euo pipefail
exe=$1
mpirun=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
args=(run lj-fluid --preset tiny --set n_cells=6 --set output.every=100 --set progress_interval=0)
"$exe" "${args[@]}" -o "$dir/one" >/dev/null
"$mpirun" -q --allow-run-as-root --oversubscribe -np 4 "$exe" "${args[@]}" -o "$dir/four" >/dev/null
/usr/bin/python3 "$(dirname "$0")/check_h5md.py" 1 "$dir/one/trajectory.h5" 4 "$dir/four/trajectory.h5"

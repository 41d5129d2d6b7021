#!/usr/bin/env bash
# MDAnalysis reads a trajectory written on 2 ranks; exit 77 (a skip) without MDAnalysis.
# usage: mdanalysis_reads.sh EMERGENT MPIRUN
set -euo pipefail
exe=$1
mpirun=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$mpirun" -q --allow-run-as-root --oversubscribe -np 2 "$exe" run lj-fluid --preset tiny \
  --set n_cells=6 --set output.every=100 --set progress_interval=0 -o "$dir" >/dev/null
set +e
/usr/bin/python3 "$(dirname "$0")/check_mdanalysis.py" "$dir/trajectory.h5"
exit $?

#!/usr/bin/env bash
# Trajectory sidecars in every ParaView XDMF reader (XDMFReader, Xdmf3ReaderS, Xdmf3ReaderT):
# a WCA fluid on 1 rank and the drum (spheres and rigid bodies) on 2 ranks, each opened and its
# content checked against the H5MD file (tests/io/xdmf_readers.py). Needs Debian's paraview and
# python3-paraview (`scripts/setup --tests` installs them): missing, the test fails;
# EMERGENT_TEST_PARAVIEW=0 skips it (exit 77, reported as skipped).
# usage: xdmf_readers.sh EMERGENT MPIRUN
set -euo pipefail
exe=$1
mpirun=$2
[ "${EMERGENT_TEST_PARAVIEW:-1}" = 0 ] && { echo "skipped: EMERGENT_TEST_PARAVIEW=0"; exit 77; }
command -v pvpython >/dev/null || { echo "FAIL: pvpython not installed (bash scripts/setup --tests installs ParaView)"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$exe" run lj-fluid --preset tiny --set output.every=50 --set progress_interval=0 -o "$dir/fluid" >/dev/null
"$mpirun" -q --allow-run-as-root --oversubscribe -np 2 "$exe" run rotating-drum --preset tiny \
  --set output.every=250 --set progress_interval=0 -o "$dir/drum" >/dev/null
for run in fluid drum; do
  # pvpython prints ParaView's own start-up lines; only the checks' lines matter.
  out=$(pvpython "$(dirname "$0")/xdmf_readers.py" "$dir/$run" 2>&1) && rc=0 || rc=$?
  grep -E "^(XDMF|Xdmf|FAIL|ok)" <<<"$out" || true
  [ $rc = 0 ] || { echo "FAIL ($run): pvpython exited with $rc"; tail -20 <<<"$out"; exit 1; }
done

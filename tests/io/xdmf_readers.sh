#!/usr/bin/env bash
# Trajectory sidecars in every ParaView XDMF reader (XDMFReader, Xdmf3ReaderS, Xdmf3ReaderT):
# a WCA fluid on 1 rank, the drum (spheres and rigid bodies) and capsomers (bodies with the
# scene's cluster labels) on 2 ranks, each opened and its content checked against the H5MD file
# (tests/io/xdmf_readers.py). The capsomers' labels are checked too: the closed shell they start
# as is one cluster of 60, and the last frame's largest cluster is the run's last measure. Needs Debian's paraview and
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
"$mpirun" -q --allow-run-as-root --oversubscribe -np 2 "$exe" run capsid-assembly --preset tiny \
  --set attraction=0.09 --set steps=400 --set output.every=200 --set progress_interval=0 -o "$dir/capsid" >/dev/null
/usr/bin/python3 - "$dir/capsid" <<'PY'
import json, sys
import h5py
import numpy as np
b = h5py.File(f"{sys.argv[1]}/trajectory.h5", "r")["particles/bodies"]
cluster, size = b["cluster/value"], b["cluster_size/value"]
assert np.all(cluster[0] == 0) and np.all(size[0] == 60), "the starting shell is not one cluster of 60"
assert np.all(b["bonds/value"][0] == 5), "the starting shell's capsomers do not have 5 bonds each"
largest = json.load(open(f"{sys.argv[1]}/summary.json"))["scene_measures"]["largest_cluster"]
assert size[-1].max() == largest, f"last frame's largest cluster {size[-1].max()}, measured {largest}"
print(f"ok: capsomers' cluster labels (start: one cluster of 60, 5 bonds each; end: largest {largest:.0f})")
PY
for run in fluid drum capsid; do
  # pvpython prints ParaView's own start-up lines; only the checks' lines matter.
  out=$(pvpython "$(dirname "$0")/xdmf_readers.py" "$dir/$run" 2>&1) && rc=0 || rc=$?
  grep -E "^(XDMF|Xdmf|FAIL|ok)" <<<"$out" || true
  [ $rc = 0 ] || { echo "FAIL ($run): pvpython exited with $rc"; tail -20 <<<"$out"; exit 1; }
done

#!/usr/bin/env bash
# The same input on the same rank count gives bitwise the same trajectory, run after run.
# usage: determinism.sh EMERGENT MPIRUN
set -euo pipefail
exe=$1
mpirun=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
for k in 1 2; do
  "$mpirun" -q --allow-run-as-root --oversubscribe -np 2 "$exe" run lj-fluid --preset tiny \
    --set n_cells=6 --set steps=1000 --set progress_interval=0 -o "$dir/run$k" >/dev/null
done
/usr/bin/python3 - "$dir" <<'PY'
import sys, h5py, numpy as np
a, b = (h5py.File(f"{sys.argv[1]}/run{k}/trajectory.h5", "r") for k in (1, 2))
for name in ("position", "velocity", "image"):
    if not np.array_equal(a[f"particles/all/{name}/value"][:], b[f"particles/all/{name}/value"][:]):
        print(f"FAIL: {name} differs between identical runs"); sys.exit(1)
if not np.array_equal(a["observables/total_energy/value"][:], b["observables/total_energy/value"][:]):
    print("FAIL: energies differ"); sys.exit(1)
print("ok: two identical 2-rank runs are bitwise identical")
PY

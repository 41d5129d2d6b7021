#!/usr/bin/env bash
# Wall tallies (energy each thermal wall and wall layer gave the fluid) go on across a restart:
# a rayleigh-benard run stopped and continued reports the same cumulative wall energies as the
# uninterrupted run, on 2 ranks and continued on 1.
# usage: restart_tallies.sh EMERGENT MPIRUN
set -euo pipefail
exe=$1
mpirun=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
run() { local np=$1; shift; "$mpirun" -q --allow-run-as-root --oversubscribe -np "$np" "$exe" run "$@" >/dev/null; }
common=(--preset tiny --set sample_every=50 --set progress_interval=0)
run 2 rayleigh-benard "${common[@]}" --set steps=600 -o "$dir/straight"
run 2 rayleigh-benard "${common[@]}" --set steps=300 --checkpoint-every 300 -o "$dir/first"
run 2 --restart "$dir/first/checkpoint.h5" --set steps=600 --set checkpoint_every=0 -o "$dir/same"
run 1 --restart "$dir/first/checkpoint.h5" --set steps=600 --set checkpoint_every=0 -o "$dir/other"
/usr/bin/python3 - "$dir" <<'PY'
import sys, h5py, numpy as np
d = sys.argv[1]
def series(run, name):
    f = h5py.File(f"{d}/{run}/{'trajectory.h5' if run == 'straight' else 'trajectory.from300.h5'}", "r")
    g = f[f"observables/{name}"]
    return dict(zip(g["step"][:], g["value"][:].reshape(len(g["step"]), -1)))
bad = []
for name in ("bottom_wall_energy", "top_wall_energy", "wall_layer_energy"):
    ref = series("straight", name)
    for run, tol in (("same", 1e-12), ("other", 1e-6)):
        got = series(run, name)
        steps = [s for s in got if s in ref and s > 300]
        if not steps:
            bad.append(f"{run}: no {name} samples after the restart")
            continue
        # Same rank count: the same sums, regrouped (restored global + new partials): round-off.
        # One rank: the trajectory itself differs by summation order after the restart.
        worst = max(np.abs(got[s] - ref[s]).max() / (1 + np.abs(ref[s]).max()) for s in steps)
        if worst > tol:
            bad.append(f"{run}: {name} differs from the straight run by {worst:.3g} (relative)")
if bad:
    print("FAIL:", *bad, sep="\n  ")
    sys.exit(1)
print("ok: wall tallies continue across restarts")
PY

#!/usr/bin/env bash
# The checking back end (particle data kept apart from the host copy, which is poisoned while
# its current values live there) gives bitwise the host back end's results for every scene, on
# 1 and 2 ranks, and a checkpoint written on one back end continues bitwise on the other. A
# sync the step forgets shows here as NaN or as a stale array: the runs then differ or stop.
# usage: backends_agree.sh EMERGENT MPIRUN
set -euo pipefail
exe=$1
mpirun=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
run() { local np=$1; shift; "$mpirun" -q --allow-run-as-root --oversubscribe -np "$np" "$exe" run "$@" >/dev/null; }
# Frames every 50 steps and field frames, so the comparison sees the run as it goes.
common=(--preset tiny --set progress_interval=0 --set output.every=50 --set fields.interval=100
        --set fields.sample_every=10)
pairs=()
# Both back ends with the same list layout, the device's (full), so the host runs the device's
# loops too.
for scene in lj-fluid granular-bed planar-couette rayleigh-benard rotating-drum taylor-couette \
             vibrated-sawtooth capsid-assembly; do
  layout=full  # every scene's force terms have a back-end form
  # The sawtooth's tiny run is 110 cycles: its settling and 10 cycles suffice here.
  extra=()
  [ $scene = vibrated-sawtooth ] && extra=(--set steps=5000 --set big_fraction=0.3)
  for np in 1 2; do
    for backend in host checking; do
      run "$np" "$scene" "${common[@]}" "${extra[@]}" --set backend=$backend --set neighbour_list=$layout \
        -o "$dir/$scene.np$np.$backend"
    done
    pairs+=("$scene.np$np.host:$scene.np$np.checking")
  done
done
# Across back ends through a checkpoint: 400 steps straight on the host, against 250 on one
# back end and the rest on the other (lj-fluid).
restart=(--set n_cells=6 --set equilibration_steps=100 --set sample_every=20 --set progress_interval=0
         --set neighbour_list=full)
run 2 lj-fluid "${restart[@]}" --set steps=300 -o "$dir/straight"
for first in host checking; do
  other=$([ $first = host ] && echo checking || echo host)
  run 2 lj-fluid "${restart[@]}" --set steps=150 --set backend=$first --checkpoint-every 250 -o "$dir/from.$first"
  run 2 --restart "$dir/from.$first/checkpoint.h5" --set steps=300 --set checkpoint_every=0 \
    --set backend=$other -o "$dir/from.$first"
  mkdir -p "$dir/cont.$first" && mv "$dir/from.$first/trajectory.from250.h5" "$dir/cont.$first/trajectory.h5"
  pairs+=("straight:cont.$first:last")
done
/usr/bin/python3 - "$dir" "${pairs[@]}" <<'PY'
import os, sys, h5py, numpy as np
d, pairs = sys.argv[1], sys.argv[2:]
bad, compared = [], 0
def datasets(f):
    out = {}
    f.visititems(lambda name, obj: out.__setitem__(name, obj) if isinstance(obj, h5py.Dataset) else None)
    return out
for pair in pairs:
    a, b, *mode = pair.split(":")
    for file in ("trajectory.h5", "fields.h5"):
        pa, pb = f"{d}/{a}/{file}", f"{d}/{b}/{file}"
        if not os.path.exists(pa) and not os.path.exists(pb):
            continue
        if not (os.path.exists(pa) and os.path.exists(pb)):
            bad.append(f"{b}: {file} exists on one side only"); continue
        da, db = datasets(h5py.File(pa, "r")), datasets(h5py.File(pb, "r"))
        if mode:  # a continuation: its last frame against the straight run's last
            names = [n for n in da if n.startswith("particles/all/") and n.endswith("/value")]
            pick = lambda x: x[-1]
        else:
            names = sorted(set(da) | set(db))
            pick = lambda x: x[()]
        for n in names:
            if n not in da or n not in db:
                bad.append(f"{b}/{file}: {n} on one side only"); continue
            x, y = pick(da[n]), pick(db[n])
            # Bitwise: the bytes (NaN where a measure is undefined compares equal to itself).
            if x.dtype.kind in "fiu" and (x.shape != y.shape or x.tobytes() != y.tobytes()):
                diff = np.abs(np.asarray(x, float) - np.asarray(y, float))
                bad.append(f"{b}/{file}: {n} differs from {a} (max {np.nanmax(diff) if diff.size else 'shape'})")
            compared += 1
    if not mode:
        ta, tb = (open(f"{d}/{x}/thermo.dat").read() for x in (a, b))
        if ta != tb: bad.append(f"{b}: thermo.dat differs from {a}")
for line in bad: print("FAIL:", line)
if bad: sys.exit(1)
print(f"ok: {len(pairs)} pairs of runs, {compared} datasets bitwise equal across back ends")
PY

#!/usr/bin/env bash
# A run killed with SIGKILL at a random moment leaves a readable checkpoint no older than one
# interval, from which the run finishes, and a trajectory that keeps its observables.
# usage: kill_and_restart.sh EMERGENT
set -euo pipefail
exe=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
every=50
"$exe" run lj-fluid --set n_cells=6 --set equilibration_steps=0 --set steps=200000 \
  --set progress_interval=0 --checkpoint-every $every -o "$dir/run" >/dev/null 2>&1 &
pid=$!
# Wait for the first checkpoint, then kill at a random moment 0.2-1.2 s later.
for _ in $(seq 100); do [ -f "$dir/run/checkpoint.h5" ] && break; sleep 0.1; done
sleep "0.$((RANDOM % 10 + 2))"
kill -9 "$pid"
wait "$pid" 2>/dev/null || true
/usr/bin/python3 - "$dir/run/checkpoint.h5" "$every" <<'PY'
import sys, h5py
f = h5py.File(sys.argv[1], "r")
step = int(f["checkpoint"].attrs["step"])
assert step > 0 and step % int(sys.argv[2]) == 0, f"checkpoint step {step}"
assert f["checkpoint/position"].shape == (864, 3)
print(f"checkpoint readable at step {step}")
PY
# The killed run's trajectory keeps its observables up to the checkpoint (one sampling
# interval, 100 steps, at most before it): series are flushed as they are written.
/usr/bin/python3 - "$dir/run/trajectory.h5" "$dir/run/checkpoint.h5" <<'PY'
import sys, h5py
t = h5py.File(sys.argv[1], "r")
step = int(h5py.File(sys.argv[2], "r")["checkpoint"].attrs["step"])
assert "temperature" in t["observables"], "killed run lost its observables"
last = int(t["observables/temperature/step"][-1])
assert last >= step - 100, f"observables end at step {last}, checkpoint at {step}"
print(f"observables kept to step {last}")
PY
# Continue a little past the checkpoint.
step=$(/usr/bin/python3 -c "import h5py,sys; print(h5py.File(sys.argv[1],'r')['checkpoint'].attrs['step'])" "$dir/run/checkpoint.h5")
"$exe" run --restart "$dir/run/checkpoint.h5" --set steps=$((step + 100)) --set checkpoint_every=0 \
  --summary-json "$dir/summary.json" >/dev/null
grep -q '"N": 864' "$dir/summary.json"
echo "ok: killed run continued from step $step"

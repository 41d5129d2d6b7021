#!/usr/bin/env bash
# The watch snapshot (DIR/snapshot.h5) and scripts/watch: on 1 and 2 ranks the snapshot holds
# exactly the run's last field frames and measures (tests/support/snapshot_check.py); a long
# history is thinned to at most 2048 samples spanning the run; a reader that opens the file
# over and over while the run rewrites it never fails (it is replaced whole by a rename); with
# output.snapshot_seconds=0 there is none; a short vector measure keeps its whole history;
# scripts/watch draws watch.png, both panels, for each kind of field slice and for a run without
# fields, follows a running job until it ends, and refuses bad input in one line (status 2).
# usage: watch_snapshot.sh EMERGENT [MPIRUN]   (MPIRUN: the one CMake found; default mpirun)
set -euo pipefail
exe=$1
mpirun=${2:-mpirun}
root=$(cd "$(dirname "$0")/../.." && pwd)
dir=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$dir"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
check=$root/tests/support/snapshot_check.py
often="--set output.snapshot_seconds=1e-9 --set progress_interval=0"
"$exe" run taylor-couette --preset tiny $often -o "$dir/tc" >/dev/null
/usr/bin/python3 "$check" "$dir/tc"
"$mpirun" -q --oversubscribe -np 2 "$exe" run rayleigh-benard --preset tiny --set fields.grid=6x6x5 $often -o "$dir/rb" >/dev/null
/usr/bin/python3 "$check" "$dir/rb"
"$exe" run capsid-assembly --preset tiny --set steps=200 $often -o "$dir/capsid" >/dev/null
/usr/bin/python3 "$check" "$dir/capsid"
# The drum's phenomenon is a short vector (core index, its random-mixture sd, their ratio): its
# history is kept whole (the check compares every component with the run's own).
"$exe" run rotating-drum --preset tiny $often -o "$dir/drum" >/dev/null
/usr/bin/python3 "$check" "$dir/drum" | tee "$dir/drum.check"
grep -q ", [1-9][0-9]* of short vectors" "$dir/drum.check" || { echo "FAIL: no short vector's history"; exit 1; }
# 5000 samples: thinned to between 1024 and 2048.
"$exe" run rayleigh-benard --preset tiny --set sample_every=1 --set steps=5000 $often -o "$dir/long" >/dev/null
/usr/bin/python3 "$check" "$dir/long" 1024
[ ! -e "$dir/long/snapshot.h5.tmp" ] || { echo "FAIL: snapshot.h5.tmp left behind"; exit 1; }
"$exe" run lj-fluid --preset tiny --set output.snapshot_seconds=0 --set progress_interval=0 -o "$dir/none" >/dev/null
[ ! -e "$dir/none/snapshot.h5" ] || { echo "FAIL: output.snapshot_seconds=0 wrote a snapshot"; exit 1; }
# A reader racing the writer, then scripts/watch following the same run to its end.
"$exe" run rayleigh-benard --preset tiny --set sample_every=1 --set steps=8000 \
  --set output.snapshot_seconds=0.001 --set progress_interval=0 -o "$dir/race" >/dev/null &
run_pid=$!
/usr/bin/python3 - "$dir/race" "$run_pid" <<'PY'
import os, sys, time
import h5py
run, pid = sys.argv[1], int(sys.argv[2])
reads = fails = 0
def alive():
    try:
        os.kill(pid, 0)
        return True
    except OSError:
        return False
deadline = time.time() + 120
while alive() and time.time() < deadline:
    if not os.path.exists(f"{run}/snapshot.h5"):
        time.sleep(0.01)
        continue
    try:
        with h5py.File(f"{run}/snapshot.h5", "r") as f:
            f["measures/temperature/value"][:]
            int(f.attrs["step"])
        reads += 1
    except Exception as e:  # a half-written or locked file
        fails += 1
        print("read failed:", e)
if fails or reads < 20:
    sys.exit(f"FAIL: {reads} reads of the snapshot while the run rewrote it, {fails} failed")
print(f"ok: {reads} reads of the snapshot while the run rewrote it, none failed")
PY
"$root/scripts/watch" "$dir/race" --every 0.2 >/dev/null
wait $run_pid
/usr/bin/python3 "$check" "$dir/race" 1024
# Both panels drawn on (a run without fields shows its other measures on the left).
for run in tc rb capsid drum race; do
  rm -f "$dir/$run/watch.png"
  "$root/scripts/watch" "$dir/$run" --once >/dev/null
  /usr/bin/python3 -c "
import matplotlib.image as m, sys
a = m.imread(sys.argv[1])[..., :3]
halves = (a[:, : a.shape[1] // 2], a[:, a.shape[1] // 2:])
sys.exit(int(a.shape[0] < 300 or any(h.std() < 0.05 or (h.min(axis=2) < 0.6).mean() < 0.01 for h in halves)))" "$dir/$run/watch.png" ||
    { echo "FAIL: $run/watch.png missing, or a panel blank"; exit 1; }
done
echo "ok: watch.png drawn, both panels, for taylor-couette, rayleigh-benard (1 rank and 2), capsid-assembly, rotating-drum"
for bad in "" "$dir/nosuch" "$dir/none" "$dir/tc --every -1" "$dir/tc --nosuch"; do
  rc=0
  err=$("$root/scripts/watch" $bad 2>&1 >/dev/null) || rc=$?
  [ $rc = 2 ] && [ "$(wc -l <<<"$err")" = 1 ] || { echo "FAIL: scripts/watch $bad: status $rc, $err"; exit 1; }
done
echo "ok: bad input refused in one line"

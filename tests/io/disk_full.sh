#!/usr/bin/env bash
# A full disk mid-run: exit 4, one line naming the file and the system's reason, no temporary
# file left, and the last checkpoint whole (a run continues from it to its end).
# The disk is a small tmpfs where this machine lets root mount one; otherwise the run's
# file-size limit is lowered once it is under way (prlimit; SIGXFSZ ignored, so the write
# fails with "File too large" instead of killing the process). With neither: skipped (77).
# usage: disk_full.sh EMERGENT
set -uo pipefail
exe=$1
work=$(mktemp -d)
disk=$work/disk
mkdir -p "$disk"
mounted=0
cleanup() { [ $mounted = 1 ] && umount "$disk"; rm -rf "$work"; }
trap cleanup EXIT
fail() { echo "FAIL: $*"; exit 1; }
# Checkpoints every 1000 steps, frames every 500: the disk fills after a few checkpoints.
args=(run lj-fluid --preset tiny --set steps=200000 --set output.every=500 --set sample_every=100
      --set checkpoint_every=1000 --set progress_interval=0 -o "$disk/run")
err=$work/stderr
if [ "$(id -u)" = 0 ] && mount -t tmpfs -o size=900k tmpfs "$disk" 2>/dev/null; then
  mounted=1
  reason="No space left on device"
  "$exe" "${args[@]}" >/dev/null 2>"$err"
  code=$?
elif command -v prlimit >/dev/null; then
  reason="File too large"
  (trap '' XFSZ; exec "$exe" "${args[@]}" >/dev/null 2>"$err") &
  pid=$!
  for _ in $(seq 200); do [ -f "$disk/run/checkpoint.h5" ] && break; sleep 0.05; done
  [ -f "$disk/run/checkpoint.h5" ] || { kill $pid; fail "no first checkpoint"; }
  prlimit --pid $pid --fsize=$((900 * 1024)) || { kill $pid; echo "SKIPPED: prlimit refused"; exit 77; }
  wait $pid
  code=$?
else
  echo "SKIPPED: cannot mount a tmpfs or lower a file-size limit here"
  exit 77
fi
msg=$(cat "$err")
[ "$code" = 4 ] || fail "exit $code (want 4): $msg"
[ "$(wc -l <"$err")" = 1 ] || fail "want one line on stderr, got: $msg"
grep -qE "^emergent: I/O error: cannot write '$disk/run/[a-z0-9_.]+': .*$reason" <<<"$msg" \
  || fail "the line does not name the file and '$reason': $msg"
ls "$disk/run" | grep -q '\.tmp$' && fail "a temporary file was left: $(ls "$disk/run")"
step=$(/usr/bin/python3 - "$disk/run/checkpoint.h5" <<'PY'
import sys, h5py
f = h5py.File(sys.argv[1], "r")
step = int(f["checkpoint"].attrs["step"])
assert step >= 1000 and step % 1000 == 0, step
assert f["checkpoint/position"].shape == (256, 3)
print(step)
PY
) || fail "the last checkpoint is not whole"
"$exe" run --restart "$disk/run/checkpoint.h5" --set steps=$((step + 1000)) --set progress_interval=0 \
  -o "$work/continued" >/dev/null || fail "the run does not continue from the last checkpoint"
echo "ok (exit 4): $msg"

#!/usr/bin/env bash
# A phenomenon check that must fail: benchmarks/phenomena.sh on a tiny run set up so that the
# phenomenon cannot be there (below onset, no heating, no rotation). Passes only when the
# checker ran and judged the run absent (exit 1, a FAIL verdict last), so the checker is shown
# able to fail; a crashed run or a checker that cannot read the run (exit 2) is a failure here.
# usage: control.sh EMERGENT SCENE [phenomena.sh arguments...]
set -u
export EMERGENT_EXE=$1
scene=$2
shift 2
root=$(cd "$(dirname "$0")/../.." && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
log=$("$root/benchmarks/phenomena.sh" "$scene" --preset tiny --ranks 1 --out "$out" "$@" 2>&1)
code=$?
echo "$log"
last=$(tail -n 1 <<<"$log")
[ "$code" -eq 1 ] || { echo "FAIL: phenomena.sh exit $code (want 1: the check judged and failed)"; exit 1; }
grep -q "^FAIL: $scene: " <<<"$last" || { echo "FAIL: last line is not the scene's FAIL verdict"; exit 1; }
echo "ok: the $scene check fails on its control"

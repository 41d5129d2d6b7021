#!/usr/bin/env bash
# phenomena.sh tells a run stopped on request (the engine's exit 5, a checkpoint left) from one
# that failed: "STOPPED ... --continue" and exit 3, its checkpoint kept, against "ERROR ...
# failed" and exit 2. The engine is stood in for by a script that leaves what each case leaves.
# usage: stopped_run.sh
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
# stand_in NAME CODE checkpoint|none: an "emergent" that exits CODE, leaving a checkpoint where asked.
stand_in() {
  cat >"$dir/$1" <<STUB
#!/usr/bin/env bash
while [ \$# -gt 0 ]; do [ "\$1" = -o ] && out=\$2; shift; done
mkdir -p "\$out"
[ "$3" = checkpoint ] && : >"\$out/checkpoint.h5"
exit $2
STUB
  chmod +x "$dir/$1"
}
stand_in emergent_5 5 checkpoint
stand_in emergent_4 4 none
stand_in emergent_5_bare 5 none
# One more: exit 5 for a run into a folder named capsid-assembly (with a checkpoint), 4 elsewhere.
cat >"$dir/emergent_mixed" <<'STUB'
#!/usr/bin/env bash
while [ $# -gt 0 ]; do [ "$1" = -o ] && out=$2; shift; done
mkdir -p "$out"
case $out in *capsid-assembly*) : >"$out/checkpoint.h5"; exit 5 ;; esac
exit 4
STUB
chmod +x "$dir/emergent_mixed"
log=$(EMERGENT_EXE=$dir/emergent_5 "$root/benchmarks/phenomena.sh" capsid-assembly --preset tiny --ranks 1 --out "$dir/a" 2>&1)
code=$?
[ $code -eq 3 ] || fail "a stopped run: phenomena.sh exit $code, want 3; $log"
echo "$log" | grep -q "^STOPPED: capsid-assembly: stopped on request with a checkpoint; go on with the same command and --continue" \
  || fail "a stopped run: no STOPPED line: $log"
[ -e "$dir/a/capsid-assembly/checkpoint.h5" ] || fail "a stopped run's checkpoint was removed"
log=$(EMERGENT_EXE=$dir/emergent_4 "$root/benchmarks/phenomena.sh" capsid-assembly --preset tiny --ranks 1 --out "$dir/b" 2>&1)
code=$?
[ $code -eq 2 ] || fail "a failed run: phenomena.sh exit $code, want 2; $log"
echo "$log" | grep -q "^ERROR: capsid-assembly: the run failed (exit 4" || fail "a failed run: no ERROR line: $log"
# Exit 5 without a checkpoint is no stop to go on from: a failure.
log=$(EMERGENT_EXE=$dir/emergent_5_bare "$root/benchmarks/phenomena.sh" capsid-assembly --preset tiny --ranks 1 --out "$dir/c" 2>&1)
code=$?
[ $code -eq 2 ] || fail "exit 5 without a checkpoint: phenomena.sh exit $code, want 2; $log"
echo "$log" | grep -q "^ERROR: capsid-assembly: the run failed (exit 5" || fail "exit 5 without a checkpoint: no ERROR line: $log"
# A failed run outranks a stopped one, in either order.
for order in "capsid-assembly rayleigh-benard" "rayleigh-benard capsid-assembly"; do
  rm -rf "$dir/d"
  log=$(EMERGENT_EXE=$dir/emergent_mixed "$root/benchmarks/phenomena.sh" $order --preset tiny --ranks 1 --out "$dir/d" 2>&1)
  code=$?
  [ $code -eq 2 ] || fail "a stopped and a failed run ($order): phenomena.sh exit $code, want 2; $log"
  echo "$log" | grep -q "^STOPPED: capsid-assembly" && echo "$log" | grep -q "^ERROR: rayleigh-benard: the run failed (exit 4" \
    || fail "a stopped and a failed run ($order): not both verdicts: $log"
done
echo "ok: stopped run exit 3 with STOPPED; failed run, exit 5 without a checkpoint, and a failed run beside a stopped one exit 2 with ERROR"

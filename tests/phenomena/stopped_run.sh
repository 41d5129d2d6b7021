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
# stand_in CODE [checkpoint]: an "emergent" that exits CODE, leaving a checkpoint where asked.
stand_in() {
  cat >"$dir/emergent_$1" <<STUB
#!/usr/bin/env bash
while [ \$# -gt 0 ]; do [ "\$1" = -o ] && out=\$2; shift; done
mkdir -p "\$out"
[ "$2" = checkpoint ] && : >"\$out/checkpoint.h5"
exit $1
STUB
  chmod +x "$dir/emergent_$1"
}
stand_in 5 checkpoint
stand_in 4 none
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
echo "ok: stopped run exit 3 with STOPPED, failed run exit 2 with ERROR"

#!/usr/bin/env bash
# Every phenomenon check passes and fails on stored evidence: for each of the five scenes (the
# capsid twice: capsid-assembly, its closed shell, and capsid-assembly-monomers), an
# excerpt of a logged run that shows the phenomenon (benchmarks/logs/phenomena_excerpts/SCENE/
# pass) must PASS, and one of its control, the same preset and length with the cause taken away
# (.../control: no attraction, a flat base, a drum at rest, a layer too narrow for a cell,
# rotation below onset, half the attraction), must FAIL; each verdict must be the one logged when the run ended
# (check.log), so the excerpt (scripts/excerpt_run: parameters and observables, no particle
# frames) holds all the check reads. Each excerpt stays within 1 MiB.
# usage: excerpts.sh SCRIPTS_DIR EXCERPTS_DIR [SCENE...]   (default: all six)
# Exit: 0 every stored excerpt judged as logged and none missing; 1 a verdict or size wrong;
# 77 (ctest: skipped) every stored one right but some excerpt not stored yet, named.
set -u
scripts=$1
root=$2
shift 2
scenes=${*:-taylor-couette rayleigh-benard rotating-drum vibrated-sawtooth capsid-assembly capsid-assembly-monomers}
failures=0 missing=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
for scene in $scenes; do
  for side in pass control; do
    dir=$root/$scene/$side
    want=$([ $side = pass ] && echo 0 || echo 1)
    if [ ! -f "$dir/trajectory.h5" ] || [ ! -f "$dir/check.log" ]; then
      echo "MISSING: $scene: no stored $side excerpt yet ($dir)"
      missing=$((missing + 1))
      continue
    fi
    size=$(du -cb "$dir"/trajectory*.h5 | tail -n 1 | cut -f1)
    [ "$size" -le 1048576 ] || fail "$scene $side: excerpt is $size bytes, over 1 MiB"
    out=$("$scripts/check_phenomenon" "$dir" 2>&1)
    code=$?
    verdict=$(tail -n 1 <<<"$out")
    logged=$(tail -n 1 "$dir/check.log")
    [ "$code" = "$want" ] || fail "$scene $side: check exit $code (want $want): $verdict"
    [ "$verdict" = "$logged" ] || fail "$scene $side: verdict differs from the logged one:
  now:    $verdict
  logged: $logged"
    echo "$scene $side (exit $code): $verdict"
  done
done
[ $failures -gt 0 ] && exit 1
[ $missing -gt 0 ] && { echo "SKIPPED: $missing excerpt(s) not stored yet; the stored ones judged as logged"; exit 77; }
echo "ok: every check passes on its run and fails on its control"
exit 0

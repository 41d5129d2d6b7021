#!/usr/bin/env bash
# scripts/slurm/paper: every row of its table names a preset the scene has, each prints a
# submission of scripts/slurm/emergent.sbatch with that preset, and bad input is one line, status 2.
# usage: paper_submit.sh EMERGENT
set -euo pipefail
exe=$1
paper=scripts/slurm/paper
rows=$(sed -n '/^table="/,/^"/p' $paper | awk 'NF == 4 {print $1}')
[ "$(wc -w <<<"$rows")" -ge 8 ] || { echo "FAIL: the table has $(wc -w <<<"$rows") rows"; exit 1; }
for target in $rows; do
  scene=${target%%:*} preset=${target#*:}
  "$exe" help "$scene" | sed -n '/^presets:/,$p' | grep -q "^  $preset:" \
    || { echo "FAIL: $scene has no preset '$preset'"; exit 1; }
  for kind in cpu gpu; do
    out=$($paper "$target" $kind /tmp/unused --dry-run)
    grep -q "emergent.sbatch $scene --preset $preset --set backend=$([ $kind = cpu ] && echo host || echo cuda) -o /tmp/unused$" <<<"$out" \
      || { echo "FAIL: $target $kind: $out"; exit 1; }
  done
done
check_bad() {  # expected words, then the arguments
  local want=$1; shift
  local err rc=0
  err=$($paper "$@" 2>&1 >/dev/null) || rc=$?
  [ $rc = 2 ] && [ "$(wc -l <<<"$err")" = 1 ] && grep -q "$want" <<<"$err" \
    || { echo "FAIL: '$*' gave status $rc and: $err"; exit 1; }
}
check_bad "not a paper-scale preset" lj-fluid:small cpu out
check_bad "give cpu or gpu" taylor-couette:paper tpu out
check_bad "give a range" taylor-couette:paper cpu out --seeds x
check_bad "unknown option" taylor-couette:paper cpu out --bogus
check_bad "usage" taylor-couette:paper
CORES_PER_NODE=0 check_bad "CORES_PER_NODE" taylor-couette:paper cpu out
echo "ok: $(wc -w <<<"$rows") paper presets, cpu and gpu submissions; bad input refused"

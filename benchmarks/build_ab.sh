#!/usr/bin/env bash
# Two builds of emergent side by side on the same state: the scene runs SETTLE steps once with
# build A (the older one: a newer build reads its checkpoint, not always the other way round)
# and leaves a checkpoint; A and B then continue it for TIMED steps in turn, REPEATS
# rounds, the one that runs first alternating, so the machine's load drifts alike over both. Reports each build's median rate and
# the median over rounds of the ratio B / A (the figure to quote: noise in one round cancels).
# usage: benchmarks/build_ab.sh RANKS SETTLE TIMED REPEATS EXE_A EXE_B SCENE [--set key=value]...
#        A_SETS / B_SETS ("key=value ..."): settings of A's or B's timed runs only (adjustable
#        ones), so one build can be set against itself (e.g. B_SETS=neighbour_list=full).
#        START=<checkpoint.h5>: time from that state instead of settling the scene (e.g. a long
#        run's clusters); SETTLE is then the checkpoint's step.
set -euo pipefail
cd "$(dirname "$0")/.."
ranks=$1 settle=$2 timed_steps=$3 repeats=$4 exe_a=$5 exe_b=$6 scene=$7
shift 7
. benchmarks/common.sh
if [ -n "${START:-}" ]; then
  mkdir -p "$work/settle" && cp "$START" "$work/settle/checkpoint.h5"
else
  settle_checkpoint "$exe_a" "$ranks" "$settle" "$scene" "$@"
fi
rate() {
  local sets=() kv
  for kv in $([ "$2" = a ] && echo "${A_SETS:-}" || echo "${B_SETS:-}"); do sets+=(--set "$kv"); done
  # Each timed run into an empty folder of its own, not over the last one with --overwrite,
  # which an older build does not know.
  rm -rf "$work/timed"
  mpirun --oversubscribe -np "$ranks" "$1" run --restart "$work/settle/checkpoint.h5" \
    --set steps=$((settle + timed_steps)) --set checkpoint_every=0 --set progress_interval=0 \
    "${sets[@]}" -o "$work/timed" --summary-json "$work/s.json" >/dev/null
  summary_value "$work/s.json" bytes_per_particle >>"$work/m$2"
  summary_value "$work/s.json" atom_steps_per_second
}
for r in $(seq "$repeats"); do
  # Which build runs first alternates from round to round.
  if [ $((r % 2)) -eq 1 ]; then a=$(rate "$exe_a" a); b=$(rate "$exe_b" b)
  else b=$(rate "$exe_b" b); a=$(rate "$exe_a" a); fi
  echo "# round $r: A $a B $b" >&2
  echo "$a" >>"$work/a"; echo "$b" >>"$work/b"
  awk -v a="$a" -v b="$b" 'BEGIN {print b / a}' >>"$work/ratio"
done
[ -n "${A_SETS:-}${B_SETS:-}" ] && echo "# timed runs of A also: ${A_SETS:-(nothing)}; of B: ${B_SETS:-(nothing)}"
printf '| build (%d ranks, %d steps) | particle-steps/s (median of %d) | B/particle |\n|---|---|---|\n' \
  "$ranks" "$timed_steps" "$repeats"
printf '| A %s | %.3g | %.0f |\n' "$exe_a" "$(median <"$work/a")" "$(median <"$work/ma")"
printf '| B %s | %.3g | %.0f |\n' "$exe_b" "$(median <"$work/b")" "$(median <"$work/mb")"
printf '\nB / A: median %.3f over rounds (min %.3f, max %.3f)\n' "$(median <"$work/ratio")" \
  "$(sort -g "$work/ratio" | head -1)" "$(sort -g "$work/ratio" | tail -1)"

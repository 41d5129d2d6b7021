#!/usr/bin/env bash
# capsid-assembly hysteresis: at an attraction too weak for growth from monomers, a closed shell
# survives while an open 59-cluster (the shell less one capsomer) loses members. Runs the `small`
# preset (60 capsomers in explicit solvent, start=open_shell) and the same from start=shell, for
# each seed, and tabulates at the end: bonds, the largest cluster, complete shells, and how many
# members each start lost.
# usage: benchmarks/capsid_hysteresis.sh [ATTRACTION] [OUT]   (defaults: the preset's, and
#        benchmarks/logs/capsid_hysteresis); SEEDS (space-separated) overrides "5 6 7 8", STEPS the
#        preset's steps, SET="key=value ..." adds scene settings (e.g. SET="site_depth_outer=0.5",
#        the note's rows). Runs already complete in OUT are kept, stopped ones continued from
#        their checkpoints; the table goes to stdout.
set -euo pipefail
cd "$(dirname "$0")/.."
e=${1:-}
out=${2:-benchmarks/logs/capsid_hysteresis}
. benchmarks/common.sh
mkdir -p "$out"
seeds=${SEEDS:-"5 6 7 8"}
extra=()
[ -n "$e" ] && extra+=(--set attraction="$e")
[ -n "${STEPS:-}" ] && extra+=(--set steps="$STEPS")
for kv in ${SET:-}; do extra+=(--set "$kv"); done
echo "# capsid_hysteresis.sh ${e:-(preset attraction)} ${STEPS:-(preset steps)}${SET:+; SET=\"$SET\"}; $(run_stamp)"
commit_line
for seed in $seeds; do
  for start in shell open_shell; do
    dir="$out/${start}_seed$seed"
    [ -f "$dir/summary.json" ] && continue
    start_or_resume "$dir" capsid-assembly --preset small --set start=$start --set seed="$seed" "${extra[@]}" \
      --set progress_interval=0
    "$exe" run "${run_args[@]}" -o "$dir" >/dev/null
  done
done
/usr/bin/python3 - "$out" $seeds <<'PY'
import json, sys
out, seeds = sys.argv[1], sys.argv[2:]
print("# seed  start       bonds  largest  shells  lost   steps  wall_s")
lost = {"shell": [], "open_shell": []}
for seed in seeds:
    for start, members in (("shell", 60), ("open_shell", 59)):
        s = json.load(open(f"{out}/{start}_seed{seed}/summary.json"))
        m = s["scene_measures"]
        lost[start].append(members - m["largest_cluster"])
        print(f"{seed:5s}  {start:10s}  {m['bonds']:5.0f}  {m['largest_cluster']:7.0f}  {m['complete_shells']:6.0f}"
              f"  {members - m['largest_cluster']:4.0f}  {s['steps']:6d}  {s['wall_seconds']:6.0f}")
for start, l in lost.items():
    print(f"# {start}: members lost {l} (mean {sum(l) / len(l):.1f})")
PY

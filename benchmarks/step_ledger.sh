#!/usr/bin/env bash
# The step ledger of every scene (Simulation::step_ledger): the most passes over particles,
# read-backs, collectives and arrays moved that one plain step, one sampled step and one list
# build took, on the `checking` back end (which counts what a device run would launch and read
# back) on 1 and 2 ranks. Counts, not times: this machine measures what a GPU would do.
# usage: benchmarks/step_ledger.sh [PRESET] [SCENE...]   (default: tiny, every scene)
set -euo pipefail
cd "$(dirname "$0")/.."
. benchmarks/common.sh
preset=${1:-tiny}
shift || true
scenes=${*:-$("$exe" list | awk '{print $1}')}
echo "# step ledger, preset $preset, backend checking; $(git rev-parse --short HEAD 2>/dev/null || echo '?'); $(date -u +%FT%TZ)"
printf '%-36s %3s  %-26s %-26s %-26s\n' scene np "plain: pass/read/coll/arr" "sampled" "list build"
# lj-fluid also without its thermostat: the WCA speed benchmark's physics (preset bench).
runs=()
for scene in $scenes; do
  runs+=("$scene:")
  [ "$scene" = lj-fluid ] && runs+=("lj-fluid:thermostat=none")
done
for entry in "${runs[@]}"; do
  scene=${entry%%:*} extra=${entry#*:}
  for np in 1 2; do
    run=$work/$scene.$np.${extra:-plain}
    mpirun -q --oversubscribe -np $np "$exe" run "$scene" --preset "$preset" --set backend=checking \
      --set progress_interval=0 ${extra:+--set $extra} -o "$run" --summary-json "$run.json" >/dev/null
    python3 - "$run.json" "$scene${extra:+ ($extra)}" "$np" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))["step_ledger"]
def w(k):
    x = s[k]
    return f'{x["passes"]}/{x["read_backs"]}/{x["collectives"]}/{x["arrays"]}'
print(f'{sys.argv[2]:<36} {sys.argv[3]:>3}  {w("plain_step"):<26} {w("sampled_step"):<26} {w("list_build"):<26}'
      f' ({s["plain_steps"]} plain, {s["sampled_steps"]} sampled, {s["builds"]} builds)')
PY
  done
done

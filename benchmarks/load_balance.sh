#!/usr/bin/env bash
# Wall time per step with equal slabs (balance=none) and with planes moved by cost
# (balance=cost), the same scene, parameters and rank count, ROUNDS rounds in alternating
# order: medians, the median of per-round time ratios with min-max, the ranks' work imbalance
# (list entries + 2 per particle, max/mean) and compute imbalance (slowest rank's force +
# integration less the mean), and peak memory per particle.
# usage: benchmarks/load_balance.sh SCENE RANKS [-- SCENE_ARGS...]
#   benchmarks/load_balance.sh rayleigh-benard 2 -- --preset tiny --set width_x=40 --set width_y=40 --set height=40
#   ROUNDS (5), STEPS (2000, after EQUILIBRATION 200 unmeasured), EVERY (balance.every, 500),
#   NONE_GRID / COST_GRID (the grid of each side, default auto: the scene's choice).
# More ranks than cores are oversubscribed: such times check the mechanics, not the gain.
set -euo pipefail
cd "$(dirname "$0")/.."
. benchmarks/common.sh
die() { echo "load_balance.sh: error: $*" >&2; exit 2; }
[ $# -ge 2 ] || die "usage: benchmarks/load_balance.sh SCENE RANKS [-- SCENE_ARGS...]"
scene=$1 np=$2
shift 2
[[ "$np" =~ ^[1-9][0-9]*$ ]] || die "'$np' is not a rank count"
[ "${1:-}" = "--" ] && shift
args=("$@")
rounds=${ROUNDS:-5} steps=${STEPS:-2000} eq=${EQUILIBRATION:-200} every=${EVERY:-500}
none_grid=${NONE_GRID:-auto} cost_grid=${COST_GRID:-auto}
build_header
echo "# load_balance.sh $scene $np -- ${args[*]}; rounds $rounds, steps $steps after $eq, balance.every $every;" \
     "grids: none $none_grid, cost $cost_grid"
[ "$np" -gt "$(nproc)" ] && echo "# $np ranks on $(nproc) cores: oversubscribed, times are no evidence of a gain"
for ((round = 1; round <= rounds; ++round)); do
  order=(none cost)
  [ $((round % 2)) = 0 ] && order=(cost none)  # alternate which side runs first
  for side in "${order[@]}"; do
    grid=$none_grid
    [ "$side" = cost ] && grid=$cost_grid
    mpirun -q --oversubscribe -np "$np" "$exe" run "$scene" "${args[@]}" --set balance="$side" --set balance.every="$every" --set grid="$grid" \
      --set equilibration_steps="$eq" --set steps="$steps" --set progress_interval=0 \
      --summary-json "$work/${side}_$round.json" >/dev/null 2>&1 ||
      { echo "load_balance.sh: $side run of round $round failed" >&2; exit 1; }
  done
done
/usr/bin/python3 - "$work" "$rounds" <<'PY'
import json, statistics, sys
work, rounds = sys.argv[1], int(sys.argv[2])
runs = {s: [json.load(open(f"{work}/{s}_{r}.json")) for r in range(1, rounds + 1)] for s in ("none", "cost")}
med = lambda s, f: statistics.median(f(x) for x in runs[s])
steps = runs["none"][0]["steps"]
print(f"# N = {runs['none'][0]['N']}, {runs['none'][0]['ranks']} ranks; medians of {rounds} rounds")
print("# balance  grid    ms/step  imbalance_ms/step  work_imbalance  rebalances  B/particle")
for s in ("none", "cost"):
    print(f"  {s:7s}  {runs[s][0]['grid']:6s}  {med(s, lambda x: x['wall_seconds'] / steps * 1e3):7.3f}"
          f"  {med(s, lambda x: x['seconds_imbalance'] / steps * 1e3):17.4f}"
          f"  {med(s, lambda x: x['cost_imbalance']):14.3f}  {runs[s][0]['rebalances']:10d}"
          f"  {med(s, lambda x: x['bytes_per_particle']):10.0f}")
ratios = sorted(a["wall_seconds"] / b["wall_seconds"] for a, b in zip(runs["none"], runs["cost"]))
print(f"# time none / cost per round: median {statistics.median(ratios):.3f} (min {ratios[0]:.3f}, max {ratios[-1]:.3f})")
PY

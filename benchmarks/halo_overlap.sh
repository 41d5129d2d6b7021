#!/usr/bin/env bash
# Time blocked on ghost data per step with the blocking refresh (halo_overlap=off) and with
# the refresh overlapped with the interior pair forces (on): the same scene, parameters and
# ranks, ROUNDS rounds in alternating order. Reports medians of wall time per step, halo wait
# per step (slowest rank: the whole blocking exchange when off; the time left waiting in
# MPI_Waitall when on), communication per step, the interior fraction, peak memory per
# particle, and the median of per-round wall-time ratios off/on with min-max.
# usage: benchmarks/halo_overlap.sh SCENE RANKS [-- SCENE_ARGS...]
#   benchmarks/halo_overlap.sh lj-fluid 2 -- --set n_cells=16
#   ROUNDS (5), STEPS (2000, after EQUILIBRATION 200 unmeasured).
# More ranks than cores are oversubscribed: such times check the mechanics, not the gain.
set -euo pipefail
cd "$(dirname "$0")/.."
. benchmarks/common.sh
die() { echo "halo_overlap.sh: error: $*" >&2; exit 2; }
[ $# -ge 2 ] || die "usage: benchmarks/halo_overlap.sh SCENE RANKS [-- SCENE_ARGS...]"
scene=$1 np=$2
shift 2
[[ "$np" =~ ^[1-9][0-9]*$ ]] || die "'$np' is not a rank count"
[ "$np" -ge 2 ] || die "one rank has no halo to overlap: give 2 or more ranks"
[ "${1:-}" = "--" ] && shift
args=("$@")
rounds=${ROUNDS:-5} steps=${STEPS:-2000} eq=${EQUILIBRATION:-200}
build_header
echo "# halo_overlap.sh $scene $np -- ${args[*]}; rounds $rounds, steps $steps after $eq"
[ "$np" -gt "$(nproc)" ] && echo "# $np ranks on $(nproc) cores: oversubscribed, times are no evidence of a gain"
for ((round = 1; round <= rounds; ++round)); do
  order=(off on)
  [ $((round % 2)) = 0 ] && order=(on off)  # alternate which side runs first
  for side in "${order[@]}"; do
    mpirun -q --oversubscribe -np "$np" "$exe" run "$scene" "${args[@]}" --set halo_overlap="$side" \
      --set equilibration_steps="$eq" --set steps="$steps" --set progress_interval=0 \
      --summary-json "$work/${side}_$round.json" >/dev/null 2>&1 ||
      { echo "halo_overlap.sh: $side run of round $round failed" >&2; exit 1; }
  done
done
/usr/bin/python3 - "$work" "$rounds" <<'PY'
import json, statistics, sys
work, rounds = sys.argv[1], int(sys.argv[2])
runs = {s: [json.load(open(f"{work}/{s}_{r}.json")) for r in range(1, rounds + 1)] for s in ("off", "on")}
med = lambda s, f: statistics.median(f(x) for x in runs[s])
steps = runs["off"][0]["steps"]
if not runs["on"][0]["halo_overlap"]:
    sys.exit("halo_overlap.sh: this scene cannot overlap its halo (summary halo_overlap false)")
print(f"# N = {runs['off'][0]['N']}, {runs['off'][0]['ranks']} ranks, grid {runs['off'][0]['grid']}; "
      f"medians of {rounds} rounds; interior fraction {runs['on'][0]['interior_fraction']:.3f}")
print("# overlap  ms/step  halo_wait_ms/step  communicate_ms/step  force_ms/step  B/particle")
for s in ("off", "on"):
    print(f"  {s:7s}  {med(s, lambda x: x['wall_seconds'] / steps * 1e3):7.3f}"
          f"  {med(s, lambda x: x['seconds_halo_wait'] / steps * 1e3):17.4f}"
          f"  {med(s, lambda x: x['seconds_communicate'] / steps * 1e3):19.4f}"
          f"  {med(s, lambda x: x['seconds_force'] / steps * 1e3):13.4f}"
          f"  {med(s, lambda x: x['bytes_per_particle']):10.0f}")
ratios = sorted(a["wall_seconds"] / b["wall_seconds"] for a, b in zip(runs["off"], runs["on"]))
print(f"# time off / on per round: median {statistics.median(ratios):.3f} (min {ratios[0]:.3f}, max {ratios[-1]:.3f})")
waits = sorted(a["seconds_halo_wait"] / max(b["seconds_halo_wait"], 1e-12) for a, b in zip(runs["off"], runs["on"]))
print(f"# halo wait off / on per round: median {statistics.median(waits):.2f} (min {waits[0]:.2f}, max {waits[-1]:.2f})")
PY

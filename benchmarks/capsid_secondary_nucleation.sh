#!/usr/bin/env bash
# capsid-assembly: does a cluster already present make new nuclei? From monomers at e = 0.115
# (p = 0.033, rows at 0 and 1.2) the first cluster of 6 took 38500 and 59000 tau in two seeds,
# and then 6-10 more appeared within 10000 tau (benchmarks/logs/capsid_rows0_e0.115_*.log). This
# runs the same solution with one compact patch of the shell seeded in it (start=cluster) and
# writes body frames every FRAMES steps, so that scripts/capsid_nucleus_origin can say where each
# new cluster of 6 or more came from: pieces that left another cluster, or monomers meeting
# (scripts/capsid_nucleus_origin), and what holds the clusters together at the end
# (scripts/capsid_contacts).
# usage: benchmarks/capsid_secondary_nucleation.sh OUT [SEEDS...]   (default seeds 31 32 33 34)
#   E (0.115), PATCH (20 members), TAU (8000 per run), DT (0.02, with skin 1.4: the faster step of
#   the implicit solvent, benchmarks/results/capsid.md "A longer step in the implicit solvent"),
#   FRAMES (250 steps = 5 tau), CAPSOMERS (300), PARTICLE_FRACTION (0.033) override; SET="key=value
#   ..." adds scene settings after the rows' (e.g. SET="site_depth_outer=0.25"). Runs already
#   complete in OUT are kept, stopped ones continued from their checkpoints; the table goes to
#   stdout.
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -ge 1 ] || { echo "usage: $0 OUT [SEEDS...]" >&2; exit 2; }
out=$1
shift
seeds=${*:-31 32 33 34}
. benchmarks/common.sh
e=${E:-0.115} patch=${PATCH:-20} tau=${TAU:-8000} dt=${DT:-0.02} frames=${FRAMES:-250}
steps=$(steps_for "$tau" "$dt")
extra=()
for kv in ${SET:-}; do extra+=(--set "$kv"); done
mkdir -p "$out"
echo "# capsid_secondary_nucleation.sh: e $e, a seeded patch of $patch among ${CAPSOMERS:-300} capsomers, p ${PARTICLE_FRACTION:-0.033}, implicit, rows 0 and 1.2${SET:+, $SET}; $tau tau at dt $dt, body frames every $frames steps; seeds $seeds; $(run_stamp)"
commit_line
for seed in $seeds; do
  run="$out/seed$seed"
  if [ ! -f "$run/summary.json" ]; then
    start_or_resume "$run" capsid-assembly --set site_depth_outer=0 --set capsomers="${CAPSOMERS:-300}" \
      --set particle_fraction="${PARTICLE_FRACTION:-0.033}" --set solvent=implicit --set start=cluster \
      --set cluster_size="$patch" --set attraction="$e" --set seed="$seed" --set dt="$dt" --set skin=1.4 \
      --set steps="$steps" --set sample_every="$(steps_for 50 "$dt")" --set events_every=12 \
      --set output.every="$frames" --set output.elements= --set checkpoint_every="$steps" \
      --set progress_interval=0 "${extra[@]}"
    "$exe" run "${run_args[@]}" -o "$run" >/dev/null
  fi
  echo "## seed $seed"
  scripts/capsid_nucleus_origin "$run"
  # The last state with every particle (the frames above carry the bodies only), one step on
  # from the final checkpoint, for the contacts that hold the clusters together.
  if [ -f "$run/checkpoint.h5" ] && [ ! -f "$run/last/summary.json" ]; then
    mkdir -p "$run/last"
    cp "$run/checkpoint.h5" "$run/last/start.h5"
    "$exe" run --restart "$run/last/start.h5" --set steps=$((steps + 1)) --set output.every=0 \
      --set output.elements=position,species,id --set checkpoint_every=0 --set progress_interval=0 -o "$run/last" >/dev/null
  fi
  [ -f "$run/last/summary.json" ] && scripts/capsid_contacts "$run/last"
done

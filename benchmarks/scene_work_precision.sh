#!/usr/bin/env bash
# Work-precision of a flow scene: wall time per unit of simulated time against the time step's
# and the integrator's effect on what the scene measures, in a small steady state of it.
#   rayleigh-benard: a conduction layer (height 10, 30 x 30, below onset); heat flux in at the
#     hot wall and out at the cold one, mean temperature and potential energy.
#   taylor-couette: laminar circular Couette flow in a quadrant wedge (r_i 10, gap 5, periodic
#     length 40, omega 0.2, Re ~ 9); torque of the inner and the outer cylinder on the fluid,
#     power of the inner cylinder, mean temperature.
# A base run at dt = 0.005 reaches the steady state and leaves a checkpoint; every case
# continues it for TAU time units at its dt and integrator; the reference is velocity Verlet at
# dt = 0.001. Rates (flux, torque) are slopes of the walls' cumulative exchange over the run,
# with the standard error of 5 block slopes; means carry block standard errors. A case that
# goes unstable is reported as stopped. REPEATS timed runs per case (median wall time).
# Writes the table to stdout and OUT_DIR/work_precision.png (difference against cost).
# usage: benchmarks/scene_work_precision.sh SCENE [OUT_DIR] [REPEATS] [TAU]
#        (defaults /tmp/emergent_swp_SCENE, 3, 1000; OUT_DIR is emptied first: it must be empty
#        or this script's earlier output)
set -euo pipefail
cd "$(dirname "$0")/.."
scene=$1
out=${2:-/tmp/emergent_swp_$scene}
repeats=${3:-3}
tau=${4:-1000}
. benchmarks/common.sh
case $scene in
  rayleigh-benard)
    base_args=(--set width_x=30 --set width_y=30 --set height=10) ;;
  taylor-couette)
    base_args=(--set r_inner=10 --set gap=5 --set length=40 --set omega=0.2 --set ends=periodic) ;;
  *) echo "scene must be rayleigh-benard or taylor-couette" >&2; exit 2 ;;
esac
if [ -n "$(ls -A "$out" 2>/dev/null)" ] && [ ! -d "$out/base" ]; then
  echo "scene_work_precision.sh: $out holds other files than this script's earlier output, and would be emptied: choose another OUT_DIR" >&2
  exit 2
fi
rm -rf "$out" && mkdir -p "$out"
"$exe" run "$scene" "${base_args[@]}" --set fields.interval=0 --set equilibration_steps=40000 \
  --set steps=0 --set progress_interval=0 --checkpoint-every 40000 -o "$out/base" >/dev/null
run_case() {  # integrator dt repeat
  local dir=$out/$1_dt$2/r$3 steps every
  mkdir -p "$(dirname "$dir")"
  steps=$(awk -v dt="$2" -v t="$tau" 'BEGIN { printf "%d", t / dt + 0.5 }')
  every=$(awk -v dt="$2" 'BEGIN { printf "%d", 1 / dt + 0.5 }')  # a sample per time unit
  "$exe" run --restart "$out/base/checkpoint.h5" --set integrator="$1" --set dt="$2" \
    --set steps="$steps" --set sample_every="$every" --set checkpoint_every=0 \
    --set progress_interval=0 --summary-json "$dir.json" -o "$dir" >/dev/null 2>"$dir.err" ||
    { cat "$dir.err" >&2; rm -f "$dir.json"; }
}
run_case verlet 0.001 1
for r in $(seq "$repeats"); do
  for dt in 0.002 0.0025 0.004 0.005 0.00625 0.008; do run_case verlet "$dt" "$r"; done
  for dt in 0.0025 0.005 0.00625 0.008 0.01; do run_case omelyan "$dt" "$r"; done
done
/usr/bin/python3 scripts/scene_work_precision_report "$scene" "$out" "$out/work_precision.png"

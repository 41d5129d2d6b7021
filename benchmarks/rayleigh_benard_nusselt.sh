#!/usr/bin/env bash
# Conduction references for rayleigh-benard's Nusselt number, and the below-onset check.
# A periodic column as wide as the layer is high cannot hold a convection cell (rolls need a
# wavelength ~2 H), so it conducts at any Rayleigh number: its heat flux is the conduction flux
# of that layer. (Much narrower columns conduct less: 10 x 10 at height 20 gave 8 % less flux
# than 20 x 20, 40 x 40 and 80 x 80, which agree - the wall layers then hold only ~20 atoms.) Each run starts from the conduction profile, settles 150 tau, then the heat
# flux is averaged over 150 tau (the columns: 750 tau) in 30 frames (mean_heat_flux: mean and
# block standard error).
#   1. Below onset (height 20, g scale 1: no convection, benchmarks/results/rayleigh_benard.md): the wide layer
#      (80 x 80) against its column (20 x 20): Nusselt = ratio, expected 1.
#   2. The `small` preset's layer (height 40, g scale 0.83) in a 40 x 40 column: the conduction
#      flux its Nusselt number is measured against (the preset's conduction_flux).
# usage: benchmarks/rayleigh_benard_nusselt.sh [RANKS]    (default 2)
set -euo pipefail
cd "$(dirname "$0")/.."
ranks=${1:-2}
. benchmarks/common.sh
flux() {  # label, settings...; prints "label flux error"
  local label=$1; shift
  mpirun --oversubscribe -np "$ranks" "$exe" run rayleigh-benard --set equilibration_steps=30000 \
    --set steps=30000 --set fields.interval=1000 --set progress_interval=0 "$@" -o "$work/$label" \
    --summary-json "$work/$label.json" >/dev/null
  /usr/bin/python3 -c "import json,sys; m=json.load(open(sys.argv[1]))['scene_measures']['mean_heat_flux']; print(sys.argv[2], m[0], m[1])" \
    "$work/$label.json" "$label"
}
below_wide=$(flux below_wide --set height=20 --set width_x=80 --set width_y=80 --set gravity_scale=1)
# The columns are smaller: 5x longer, for a flux error like the wide layer's.
long=(--set steps=150000 --set fields.interval=5000)
below_narrow=$(flux below_column --set height=20 --set width_x=20 --set width_y=20 --set gravity_scale=1 "${long[@]}")
small_column=$(flux small_column --set height=40 --set width_x=40 --set width_y=40 --set gravity_scale=0.83 "${long[@]}")
printf '| run | heat flux |\n|---|---|\n'
for line in "$below_wide" "$below_narrow" "$small_column"; do
  set -- $line
  printf '| %s | %.4f +- %.4f |\n' "$1" "$2" "$3"
done
set -- $below_wide; fw=$2 ew=$3
set -- $below_narrow; fn=$2 en=$3
awk -v a="$fw" -v ea="$ew" -v b="$fn" -v eb="$en" \
  'BEGIN { r = a / b; printf "\nbelow onset: Nusselt = %.3f +- %.3f (wide / column)\n", r, r * sqrt((ea/a)^2 + (eb/b)^2) }'

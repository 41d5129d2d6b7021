#!/usr/bin/env bash
# Granular bed of rigid tetrahedra (the drum's small particle: four unit spheres at arm 0.6):
# 2304 bodies = 9216 spheres settled on a floor under gravity 1 (k_n = 2000, damping and
# friction as in granular_vs_lammps.sh), then 5000 steps timed after 200 warm-up steps on 1 and
# 2 ranks, REPEATS alternating runs. Rates count sphere-steps (the force work).
# usage: benchmarks/granular_tetrahedra.sh [REPEATS] [RANKS]    (defaults 3, "1 2")
set -euo pipefail
cd "$(dirname "$0")/.."
repeats=${1:-3}
ranks_list=${2:-"1 2"}
. benchmarks/common.sh
bed=(--set particles=tetrahedra --set nx=16 --set ny=16 --set nz=9 --set spacing=2.5 --set height=40)
"$exe" run granular-bed "${bed[@]}" --set equilibration_steps=10000 --set steps=0 \
  --set progress_interval=0 --checkpoint-every 10000 -o "$work/settle" >/dev/null
printf '| ranks | sphere-steps/s (9216 spheres in 2304 tetrahedra) | B/sphere |\n|---|---|---|\n'
for np in $ranks_list; do
  for r in $(seq "$repeats"); do
    mpirun --oversubscribe -np "$np" "$exe" run --restart "$work/settle/checkpoint.h5" \
      --set equilibration_steps=10200 --set steps=5000 --set checkpoint_every=0 \
      --set progress_interval=0 -o "$work/timed" --overwrite --summary-json "$work/s.json" >/dev/null
    grep -o '"atom_steps_per_second": [0-9.e+]*' "$work/s.json" | awk '{print $2}' >>"$work/r$np"
    grep -o '"bytes_per_particle": [0-9.e+]*' "$work/s.json" | awk '{print $2}' >>"$work/m$np"
  done
  printf '| %d | %.3g | %.0f |\n' "$np" "$(median <"$work/r$np")" "$(median <"$work/m$np")"
done

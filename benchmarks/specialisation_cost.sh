#!/usr/bin/env bash
# What compiling out unused features saves. A settled granular bed (1152 spheres) run without
# damping and friction through the specialised kernel (both compiled out) and through the
# generic kernel (compiled in, coefficients zero); and lj-fluid through its specialised and
# generic paths (below). Instruction counts under callgrind are
# exact and repeatable, unlike wall time on a shared machine (see granular_vs_lammps.sh for
# the wall-clock ratio on the 19602-sphere bed).
# usage: benchmarks/specialisation_cost.sh [REPEATS]   (wall-clock repeats, default 5)
set -euo pipefail
cd "$(dirname "$0")/.."
. benchmarks/common.sh
"$exe" run granular-bed --set nx=12 --set ny=12 --set nz=8 --set steps=0 --set progress_interval=0 \
  --checkpoint-every 15000 -o "$work/bed" >/dev/null
for kernel in specialised generic; do
  valgrind --tool=callgrind --callgrind-out-file="$work/cg.$kernel" "$exe" run \
    --restart "$work/bed/checkpoint.h5" --set steps=1000 --set gamma_n=0 --set gamma_s=0 \
    --set kernel=$kernel --set checkpoint_every=0 --set progress_interval=0 -o "$work/bed.$kernel" \
    2>"$work/vg.$kernel" >/dev/null
  grep -o 'Collected : [0-9]*' "$work/vg.$kernel" | awk '{print $3}' >"$work/ir.$kernel"
done
s=$(cat "$work/ir.specialised"); g=$(cat "$work/ir.generic")
echo "granular bed, instructions for 1000 steps: specialised $s, generic $g, generic/specialised = $(awk -v a="$g" -v b="$s" 'BEGIN {printf "%.2f", a/b}')"
# lj-fluid (WCA, rho 0.8, 2048 atoms, NVE, sampling every 100 steps): the generic pair loop
# (species table, pair damping with gamma 0, energy and virial every step, ghost velocities)
# plus a zero field and an unreached wall, against the specialised path.
for kernel in specialised generic; do
  valgrind --tool=callgrind --callgrind-out-file="$work/lj.$kernel" "$exe" run lj-fluid     --set n_cells=8 --set thermostat=none --set equilibration_steps=0 --set steps=500     --set sample_every=100 --set kernel=$kernel --set progress_interval=0 2>"$work/vl.$kernel" >/dev/null
  grep -o 'Collected : [0-9]*' "$work/vl.$kernel" | awk '{print $3}' >"$work/il.$kernel"
done
s=$(cat "$work/il.specialised"); g=$(cat "$work/il.generic")
echo "lj-fluid, instructions for 500 steps: specialised $s, generic $g, generic/specialised = $(awk -v a="$g" -v b="$s" 'BEGIN {printf "%.2f", a/b}')"
# Wall clock, lj-fluid (16384 atoms, 2000 steps, 1 rank): REPEATS alternating runs, medians.
repeats=${1:-5}
for r in $(seq "$repeats"); do
  for kernel in specialised generic; do
    "$exe" run lj-fluid --set n_cells=16 --set thermostat=none --set equilibration_steps=200 \
      --set steps=2000 --set sample_every=100 --set kernel=$kernel --set progress_interval=0 \
      --summary-json "$work/w.json" >/dev/null
    grep -o '"atom_steps_per_second": [0-9.e+]*' "$work/w.json" | awk '{print $2}' >>"$work/w.$kernel"
  done
done
s=$(median <"$work/w.specialised"); g=$(median <"$work/w.generic")
echo "lj-fluid wall clock (medians of $repeats): specialised $s, generic $g atom-steps/s, specialised/generic = $(awk -v a="$s" -v b="$g" 'BEGIN {printf "%.2f", a/b}')"

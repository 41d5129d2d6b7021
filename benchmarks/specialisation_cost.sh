#!/usr/bin/env bash
# What compiling out unused contact features saves: a settled granular bed (1152 spheres) run
# without damping and friction through the specialised kernel (both compiled out) and through
# the generic kernel (compiled in, coefficients zero). Instruction counts under callgrind are
# exact and repeatable, unlike wall time on a shared machine (see granular_vs_lammps.sh for
# the wall-clock ratio on the 19602-sphere bed).
# usage: benchmarks/specialisation_cost.sh
set -euo pipefail
cd "$(dirname "$0")/.."
exe=$PWD/build/bin/emergent
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$exe" run granular-bed --set nx=12 --set ny=12 --set nz=8 --set steps=0 --set progress_interval=0 \
  --checkpoint-every 15000 -o "$work/bed" >/dev/null
for kernel in specialised generic; do
  valgrind --tool=callgrind --callgrind-out-file="$work/cg.$kernel" "$exe" run \
    --restart "$work/bed/checkpoint.h5" --set steps=1000 --set gamma_n=0 --set gamma_s=0 \
    --set kernel=$kernel --set checkpoint_every=0 --set progress_interval=0 2>"$work/vg.$kernel" >/dev/null
  grep -o 'Collected : [0-9]*' "$work/vg.$kernel" | awk '{print $3}' >"$work/ir.$kernel"
done
s=$(cat "$work/ir.specialised"); g=$(cat "$work/ir.generic")
echo "instructions for 1000 steps: specialised $s, generic $g, generic/specialised = $(awk -v a="$g" -v b="$s" 'BEGIN {printf "%.2f", a/b}')"

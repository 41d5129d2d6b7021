#!/usr/bin/env bash
# GPU throughput of the periodic pair fluid (emergent-gpu-bench), as recorded in RESULTS.md:
# HOOMD-blue's published LJ benchmark state (N = 64000, rho = 1.0, rc = 2.5, buffer 0.4,
# kT = 1.2) and its WCA variant with a per-part profile; then WCA at rho = 0.8 from 32000 to
# 8 million atoms in double and mixed precision; then the skin at 1 million atoms, and the
# threads per particle for the two 64000-atom states and 1 million WCA atoms.
#   benchmarks/gpu_pair_fluid.sh [path/to/emergent-gpu-bench]
set -euo pipefail
exe=${1:-build/bin/emergent-gpu-bench}
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.mem,temperature.gpu --format=csv || true

# Timed steps per repeat: about 5e8 atom-steps, at least 200 steps.
steps_for() { local s=$((500000000 / $1)); echo $((s < 200 ? 200 : s)); }

echo "## HOOMD-blue benchmark states (N = 64000, rho = 1.0, kT = 1.2, buffer 0.4)"
"$exe" --cells 25 --density 1.0 --temperature 1.2 --cutoff 2.5 --skin 0.4 \
       --steps 5000 --warmup 5000 --repeats 5 --profile
"$exe" --cells 25 --density 1.0 --temperature 1.2 --cutoff 1.122462048309373 --skin 0.4 \
       --steps 10000 --warmup 5000 --repeats 5 --profile
"$exe" --cells 25 --density 1.0 --temperature 1.2 --cutoff 2.5 --skin 0.4 \
       --steps 5000 --warmup 5000 --repeats 5 --precision mixed

echo "## WCA, rho = 0.8, T = 1, skin 0.3"
for precision in double mixed; do
  for cells in 20 40 63 80 100 126; do
    n=$((4 * cells * cells * cells))
    s=$(steps_for $n)
    "$exe" --cells $cells --density 0.8 --skin 0.3 --steps $s --warmup $s --repeats 5 \
           --precision $precision
  done
done
"$exe" --cells 63 --density 0.8 --skin 0.3 --steps 500 --warmup 500 --repeats 3 --profile

echo "## WCA, rho = 0.8, 1 million atoms: skin"
for skin in 0.15 0.2 0.3 0.4 0.5; do
  "$exe" --cells 63 --density 0.8 --skin $skin --steps 500 --warmup 500 --repeats 5
done

echo "## threads per particle in the force pass (0: the automatic choice)"
for lanes in 1 2 4 8 16 32; do
  "$exe" --cells 25 --density 1.0 --temperature 1.2 --cutoff 2.5 --skin 0.4 \
         --steps 3000 --warmup 3000 --repeats 5 --lanes $lanes
  "$exe" --cells 25 --density 1.0 --temperature 1.2 --skin 0.4 \
         --steps 5000 --warmup 3000 --repeats 5 --lanes $lanes
  "$exe" --cells 63 --density 0.8 --skin 0.3 --steps 500 --warmup 500 --repeats 5 --lanes $lanes
done

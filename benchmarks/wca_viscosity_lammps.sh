#!/usr/bin/env bash
# The shear viscosity of the WCA fluid at rho = 0.465, T = 1.27 (planar-couette's mid-channel
# state at its default settings) by Green-Kubo in LAMMPS (benchmarks/in.wca_gk.lmp: N = 1372,
# dt = 0.005, 3000 tau a seed under a 5-tau Nose-Hoover thermostat, the stress autocorrelation
# integrated over 5 tau): an independent code and method for the number the planar-couette
# viscosity test compares with (tests/physics/planar_couette_viscosity.py). Each seed gives the
# mean of the three off-diagonal estimates; the result is the mean over seeds with its standard
# error (seeds are independent runs). The raw log goes to LOG.
# usage: benchmarks/wca_viscosity_lammps.sh [SEEDS] [LOG]
#   defaults: 6 benchmarks/logs/wca_viscosity_lammps_<date>.log
set -euo pipefail
cd "$(dirname "$0")/.."
seeds=${1:-6}
log=${2:-benchmarks/logs/wca_viscosity_lammps_$(date -u +%Y-%m-%d).log}
command -v lmp >/dev/null || { echo "wca_viscosity_lammps.sh: needs LAMMPS (apt-get install lammps)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMP_NUM_THREADS=1
mkdir -p "$(dirname "$log")"
input=$PWD/benchmarks/in.wca_gk.lmp
{
  echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(uname -n) $(lmp -h | sed -n 's/^Large-scale.*- \(.*\)$/\1/p' | head -n 1)"
  echo "# seed eta_xy eta_xz eta_yz (Green-Kubo, rho 0.465, T 1.27, N 1372)"
  for k in $(seq "$seeds"); do
    seed=$((87287 + 1000 * k))
    (cd "$work" && lmp -in "$input" -var seed $seed -log "$work/log.$seed" -screen none)
    sed -n 's/^GK [^ ]* [^ ]* //p' "$work/log.$seed"
  done
} | tee "$log.tmp"
/usr/bin/python3 - "$log.tmp" <<'PY' | tee -a "$log.tmp"
import sys
import numpy as np
rows = np.loadtxt(sys.argv[1], comments="#")
eta = rows[:, 1:].mean(axis=1)
print(f"# eta = {eta.mean():.4f} +- {eta.std(ddof=1) / np.sqrt(len(eta)):.4f} "
      f"(mean of {len(eta)} seeds, standard error; per seed {np.round(eta, 4).tolist()})")
PY
mv "$log.tmp" "$log"

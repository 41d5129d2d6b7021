#!/usr/bin/env bash
# The shear viscosity of the WCA fluid at rho = 0.465, T = 1.27 (planar-couette's mid-channel
# state at its default settings) by Green-Kubo in LAMMPS (benchmarks/in.wca_gk.lmp: N = 1372,
# dt = 0.005, 3000 tau a seed under a 5-tau Nose-Hoover thermostat): another code and another
# method (no walls, no flow) for the number the planar-couette viscosity test compares with
# (tests/physics/planar_couette_viscosity.py). The stress autocorrelation (averaged over the
# three off-diagonal elements) is integrated to t_c = 2.5 tau: it has decayed below 1 % of its
# start by 1 tau, and later lags add noise, not signal (the integral to 5 tau is given too).
# Each seed is an independent run; the result is the mean over seeds with its standard error.
# The raw log goes to LOG.
# usage: benchmarks/wca_viscosity_lammps.sh [SEEDS] [LOG]
#   defaults: 8 benchmarks/logs/wca_viscosity_lammps_<date>.log
set -euo pipefail
cd "$(dirname "$0")/.."
seeds=${1:-8}
log=${2:-benchmarks/logs/wca_viscosity_lammps_$(date -u +%Y-%m-%d).log}
command -v lmp >/dev/null || { echo "wca_viscosity_lammps.sh: needs LAMMPS (apt-get install lammps)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMP_NUM_THREADS=1
mkdir -p "$(dirname "$log")"
input=$PWD/benchmarks/in.wca_gk.lmp
echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(uname -n), LAMMPS $(lmp -h | sed -n 's/^Large-scale Atomic\/Molecular Massively Parallel Simulator - //p')" >"$log.tmp"
for k in $(seq "$seeds"); do
  seed=$((87287 + 1000 * k))
  mkdir "$work/$seed"
  (cd "$work/$seed" && lmp -in "$input" -var seed $seed -log log.lammps -screen none)
done
/usr/bin/python3 - "$work" 1372 0.465 1.27 2.5 <<'PY' | tee -a "$log.tmp"
import glob, os, sys
import numpy as np
work, n, rho, temp, t_c = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5])
print(f"# Green-Kubo, WCA, rho {rho}, T {temp}, N {n}; per seed: eta to {t_c} tau (xy xz yz, mean), "
      "eta to 5 tau (mean), mean temperature")
etas = []
for d in sorted(glob.glob(f"{work}/*/")):
    rows = [l.split() for l in open(f"{d}/gk_acf.dat") if l.strip() and not l.startswith("#")]
    last = [r for r in rows[-501:] if len(r) == 6]  # the final (whole-run) correlation block
    a = np.array(last[-500:], dtype=float)
    t, acf = a[:, 1] * 0.005, a[:, 3:6]
    integral = np.concatenate([np.zeros((1, 3)), np.cumsum(0.5 * (acf[1:] + acf[:-1]) * np.diff(t)[:, None], axis=0)])
    scale = (n / rho) / temp
    cut = np.searchsorted(t, t_c)
    eta_c, eta_5 = integral[cut] * scale, integral[-1] * scale
    temps = [float(l.split()[1]) for l in open(f"{d}/log.lammps") if l.split()[:1] and l.split()[0].isdigit() and len(l.split()) == 6]
    etas.append(eta_c.mean())
    print(os.path.basename(d.rstrip("/")), *(f"{x:.4f}" for x in eta_c), f"{eta_c.mean():.4f}",
          f"{eta_5.mean():.4f}", f"{np.mean(temps[1:]):.4f}")
etas = np.array(etas)
print(f"# eta = {etas.mean():.4f} +- {etas.std(ddof=1) / np.sqrt(len(etas)):.4f} (mean over "
      f"{len(etas)} seeds, standard error; Green-Kubo integral to {t_c} tau)")
PY
mv "$log.tmp" "$log"

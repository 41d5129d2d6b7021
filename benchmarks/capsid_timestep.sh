#!/usr/bin/env bash
# capsid-assembly in the implicit solvent: is a longer time step as good as the scene's 0.005?
# Without solvent atoms the fastest motions left are those of the capsomers (mass 15, their
# spheres' WCA contacts at a reduced mass of 7.5, the sites' harmonic wells), slower than an
# atom's by ~sqrt(15), so a step several times 0.005 may integrate them as well. For each DT:
#  - monomers at attraction E over TAU time units (seeds SEEDS): the capsomers' translational
#    and rotational kinetic temperatures (the Langevin target is 1; a too long step heats them),
#    the dimers formed per tau and their mean lifetime (censuses every 0.1 tau), the mean
#    potential energy per particle;
#  - a closed shell of 60 with the frictions off (the bodies' own dynamics, energy conserved):
#    the total energy's drift per particle over SHELL_TAU.
# usage: benchmarks/capsid_timestep.sh OUT DT...   E (0.1225), SEEDS ("41 42 43"), TAU (1000),
#        SHELL_TAU (200), CAPSOMERS (300, at particle_fraction 0.033), SET ("site_depth_outer=0")
#        override. Runs already complete in OUT are kept; the table goes to stdout.
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -ge 2 ] || { echo "usage: $0 OUT DT..." >&2; exit 2; }
out=$1
shift
. benchmarks/common.sh
e=${E:-0.1225}
seeds=${SEEDS:-"41 42 43"}
tau=${TAU:-1000}
shell_tau=${SHELL_TAU:-200}
capsomers=${CAPSOMERS:-300}
set_kv=${SET-site_depth_outer=0}
extra=()
for kv in $set_kv; do extra+=(--set "$kv"); done
mkdir -p "$out"
echo "# capsid_timestep.sh: dt $*; e $e; seeds $seeds; $tau tau from monomers ($capsomers capsomers, p 0.033, implicit, $set_kv); closed shell without friction $shell_tau tau; $(run_stamp)"
commit_line
steps_of() { /usr/bin/python3 -c "print(round($1 / $2))"; }
for dt in "$@"; do
  census=$(steps_of 0.1 "$dt")
  for seed in $seeds; do
    dir="$out/dt${dt}_seed$seed"
    [ -f "$dir/summary.json" ] && continue
    "$exe" run capsid-assembly "${extra[@]}" --set capsomers="$capsomers" --set particle_fraction=0.033 \
      --set solvent=implicit --set start=monomers --set attraction="$e" --set seed="$seed" --set dt="$dt" \
      --set steps="$(steps_of "$tau" "$dt")" --set sample_every="$census" --set output.every=0 \
      --set progress_interval=0 -o "$dir.tmp" >/dev/null
    mv "$dir.tmp" "$dir"
  done
  dir="$out/dt${dt}_shell"
  if [ ! -f "$dir/summary.json" ]; then
    "$exe" run capsid-assembly "${extra[@]}" --set capsomers=60 --set particle_fraction=0.033 \
      --set solvent=implicit --set start=shell --set attraction="$e" --set friction_translation=0 \
      --set friction_rotation=0 --set dt="$dt" --set steps="$(steps_of "$shell_tau" "$dt")" \
      --set sample_every="$(steps_of 1 "$dt")" --set output.every=0 --set progress_interval=0 \
      -o "$dir.tmp" >/dev/null
    mv "$dir.tmp" "$dir"
  fi
done
/usr/bin/python3 - "$out" "$seeds" "$@" <<'PY'
import json, sys
sys.path.insert(0, "scripts")
import numpy as np
from emergentpy import Run
out, seeds, dts = sys.argv[1], sys.argv[2].split(), sys.argv[3:]
def mean_err(xs):
    xs = np.asarray(xs, float)
    return xs.mean(), (xs.std(ddof=1) / np.sqrt(len(xs)) if len(xs) > 1 else float("nan"))
print("| dt | T translation | T rotation | dimers formed per tau | dimer lifetime (tau) | potential energy per particle | shell, no friction: energy drift per particle | wall s per tau (monomers) |")
print("|---|---|---|---|---|---|---|---|")
for dt in dts:
    tt, tr, rate, life, pot, wall = [], [], [], [], [], 0.0
    for seed in seeds:
        d = f"{out}/dt{dt}_seed{seed}"
        s = json.load(open(f"{d}/summary.json"))
        m = s["scene_measures"]
        t, temps = Run(d).observable("capsomer_temperature")
        t, temps = np.asarray(t, float).reshape(-1), np.asarray(temps, float).reshape(len(t), -1)
        keep = t >= 10  # the first 10 tau: the start's velocities settling
        tt.append(temps[keep, 0].mean())
        tr.append(temps[keep, 1].mean())
        span = s["steps"] * s["dt"]
        sample = s["dt"] * round(0.1 / s["dt"])
        # growth_events[0]: monomers that joined another monomer; two per dimer formed.
        rate.append(m["growth_events"][0] / 2 / span)
        ended = m["growth_events"][1] + m["loss_events"][1]
        life.append(sample * m["clusters_seen"][1] / ended if ended else float("nan"))
        pot.append(s["mean_potential_energy"])
        wall += s["wall_seconds"] / span / len(seeds)
    shell = json.load(open(f"{out}/dt{dt}_shell/summary.json"))
    cells = [dt]
    for xs, fmt in ((tt, ".4f"), (tr, ".4f"), (rate, ".3f"), (life, ".3f"), (pot, ".5f")):
        mu, err = mean_err(xs)
        cells.append(f"{mu:{fmt}} +- {err:{fmt}}")
    cells += [f"{shell['energy_drift_per_particle']:.2e}", f"{wall:.3f}"]
    print("| " + " | ".join(cells) + " |")
print("# +-: standard error of the mean over the seeds; T from the samples every 0.1 tau after the first 10 tau")
PY

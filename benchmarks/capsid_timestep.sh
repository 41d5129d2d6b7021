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
#        override. Runs already complete in OUT are kept; one that was stopped (OUT/*.tmp) runs
#        again from its start over what it left, as its wall time is measured; the table goes to
#        stdout.
#        benchmarks/capsid_timestep.sh rate CHECKPOINT TAU ROUNDS DT:SKIN...  the cost of TAU
#        time units continued from CHECKPOINT (a capsid run's state, e.g. with clusters) at each
#        step and list skin, the settings in turn in every round (their order rotated from round
#        to round): wall seconds per tau (less the start's, from a run of 10 steps) and peak
#        memory per particle, the median and range over the rounds.
set -euo pipefail
cd "$(dirname "$0")/.."
. benchmarks/common.sh
if [ "${1:-}" = rate ]; then
  [ $# -ge 5 ] || { echo "usage: $0 rate CHECKPOINT TAU ROUNDS DT:SKIN..." >&2; exit 2; }
  ckpt=$2 tau=$3 rounds=$4
  [ -f "$ckpt" ] || { echo "$0: no checkpoint $ckpt" >&2; exit 2; }
  shift 4
  settings=("$@")
  for s in "${settings[@]}"; do steps_for "$tau" "${s%%:*}" >/dev/null; done
  read -r step n < <(/usr/bin/python3 -c "import h5py,sys; h=h5py.File(sys.argv[1],'r')['checkpoint']; print(int(h.attrs['step']), int(h.attrs['n_global']))" "$ckpt")
  echo "# capsid_timestep.sh rate: from $ckpt (step $step, $n particles), $tau tau per run, $rounds rounds; $(run_stamp)"
  commit_line
  one() {  # DT SKIN STEPS -> "wall_s peak_kB"
    rm -rf "$work/rate"
    /usr/bin/time -f "%e %M" -o "$work/time" "$exe" run --restart "$ckpt" --set dt="$1" --set skin="$2" \
      --set steps=$((step + $3)) --set events_every="$(steps_for 0.25 "$1")" \
      --set progress_interval=0 --set output.every=0 --set checkpoint_every=0 -o "$work/rate" >/dev/null
    cat "$work/time"
  }
  start=$(one 0.005 0.7 10 | awk '{print $1}')
  echo "# start (10 steps): $start s"
  for ((r = 0; r < rounds; r++)); do
    for ((k = 0; k < ${#settings[@]}; k++)); do
      s=${settings[$(((k + r) % ${#settings[@]}))]}
      dt=${s%%:*} skin=${s##*:}
      steps=$(steps_for "$tau" "$dt")
      read -r wall kb < <(one "$dt" "$skin" "$steps")
      echo "round $r dt $dt skin $skin steps $steps wall $wall s_per_tau $(/usr/bin/python3 -c "print(f'{($wall - $start) / $tau:.4f}')") bytes_per_particle $((kb * 1024 / n))"
    done
  done | tee "$work/rounds"
  echo "| dt | skin | s per tau, median (min-max) | against the first setting, median of per-round ratios (min-max) | B/particle |"
  echo "|---|---|---|---|---|"
  /usr/bin/python3 - "$work/rounds" "${settings[@]}" <<'PY'
import sys, statistics as st
rows = [l.split() for l in open(sys.argv[1])]
cost = {}
for r in rows:
    cost.setdefault((r[3], r[5]), {})[int(r[1])] = (float(r[11]), int(r[13]))
base = cost[tuple(sys.argv[2].split(":"))]
for s in sys.argv[2:]:
    c = cost[tuple(s.split(":"))]
    per = [c[k][0] for k in sorted(c)]
    ratio = [base[k][0] / c[k][0] for k in sorted(c)]
    print(f"| {s.split(':')[0]} | {s.split(':')[1]} | {st.median(per):.4f} ({min(per):.4f}-{max(per):.4f}) | "
          f"{st.median(ratio):.2f} ({min(ratio):.2f}-{max(ratio):.2f}) | {max(v[1] for v in c.values())} |")
PY
  exit 0
fi
[ $# -ge 2 ] || { echo "usage: $0 OUT DT..." >&2; exit 2; }
out=$1
shift
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
for dt in "$@"; do steps_for "$tau" "$dt" >/dev/null; done  # each DT a number, checked before any run
for dt in "$@"; do
  census=$(steps_for 0.1 "$dt")
  for seed in $seeds; do
    dir="$out/dt${dt}_seed$seed"
    [ -f "$dir/summary.json" ] && continue
    "$exe" run capsid-assembly "${extra[@]}" --set capsomers="$capsomers" --set particle_fraction=0.033 \
      --set solvent=implicit --set start=monomers --set attraction="$e" --set seed="$seed" --set dt="$dt" \
      --set steps="$(steps_for "$tau" "$dt")" --set sample_every="$census" --set output.every=0 \
      --set progress_interval=0 -o "$dir.tmp" --overwrite >/dev/null
    mv "$dir.tmp" "$dir"
  done
  dir="$out/dt${dt}_shell"
  if [ ! -f "$dir/summary.json" ]; then
    "$exe" run capsid-assembly "${extra[@]}" --set capsomers=60 --set particle_fraction=0.033 \
      --set solvent=implicit --set start=shell --set attraction="$e" --set friction_translation=0 \
      --set friction_rotation=0 --set dt="$dt" --set steps="$(steps_for "$shell_tau" "$dt")" \
      --set sample_every="$(steps_for 1 "$dt")" --set output.every=0 --set progress_interval=0 \
      -o "$dir.tmp" --overwrite >/dev/null
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

#!/usr/bin/env bash
# capsid-assembly's paper-scale presets (table1, paper) in both solvents: the rate of their first
# STEPS (1000) steps from the start on RANKS (2) ranks, peak memory per particle, and the time
# their full step count would take at that rate on this machine.
# usage: benchmarks/capsid_presets_rate.sh   (STEPS, RANKS override; run it on a quiet machine)
set -euo pipefail
cd "$(dirname "$0")/.."
. benchmarks/common.sh
steps=${STEPS:-1000}
ranks=${RANKS:-2}
echo "# capsid-assembly's table1 and paper presets: the rate of their first $steps steps from the start (monomers), and the projected time of the preset's steps; $(run_stamp)"
commit_line
for preset in table1 paper; do
  for solvent in explicit implicit; do
    args=(run capsid-assembly --preset "$preset" --set solvent="$solvent" --set steps="$steps" --set sample_every="$steps"
          --set output.every=0 --set checkpoint_every=0 --set progress_interval=0 -o "$work/$preset-$solvent")
    echo "# mpirun -q --oversubscribe -np $ranks $exe ${args[*]}" | sed "s|$work|OUT|"
    start=$(date +%s.%N)
    mpirun -q --oversubscribe -np "$ranks" "$exe" "${args[@]}" >/dev/null
    total=$(echo "$(date +%s.%N) - $start" | bc)
    /usr/bin/python3 - "$work/$preset-$solvent/summary.json" "$preset" "$solvent" "$ranks" "$total" \
      "$($exe help capsid-assembly | sed -n "s/^  $preset: .* steps=\([0-9]*\).*/\1/p")" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
preset, solvent, ranks, total, full = sys.argv[2], sys.argv[3], sys.argv[4], float(sys.argv[5]), float(sys.argv[6])
rate = s["atom_steps_per_second"]
steps_per_s = rate / s["N"]
print(f"{preset} {solvent} {ranks} ranks: N {s['N']}, {rate:.3g} particle-steps/s, {steps_per_s:.1f} steps/s, "
      f"{s['bytes_per_particle']:.0f} B/particle, rebuilds {s['neighbour_rebuilds']}, wall {s['wall_seconds']:.1f} s "
      f"(with start-up {total:.0f} s); the preset's {full:.2g} steps: {full / steps_per_s / 86400:.0f} days")
PY
  done
done

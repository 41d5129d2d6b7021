#!/usr/bin/env bash
# capsid-assembly, the paper's Table 1 qualitatively: at particle fraction 0.033, runs of equal
# length over a range of attraction e and seeds, from monomers, in the implicit solvent (Langevin
# bodies at the explicit solvent's measured diffusion: fast exploration). Tabulates per run the
# largest cluster, the mass fractions by size group (1, 2-5, 6-50, 51-59, 60), complete shells
# and bonds at the end; then when mass first appears in clusters of 6 or more, and when it
# reaches half its final value. The paper's pattern: no growth at low e, shells in between,
# many mid-size clusters and no shells at high e.
# usage: benchmarks/capsid_table1.sh [OUT] [E...]   (defaults /tmp/capsid_table1; e 0.06 0.09
#        0.12 0.15); SEEDS ("21 22"), STEPS (400000), CAPSOMERS (300), SOLVENT (implicit)
#        override. Runs already complete in OUT are kept, stopped ones continued from their
#        checkpoints; the table goes to stdout.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-/tmp/capsid_table1}
shift || true
energies=${*:-0.06 0.09 0.12 0.15}
. benchmarks/common.sh
seeds=${SEEDS:-"21 22"}
steps=${STEPS:-400000}
capsomers=${CAPSOMERS:-300}
solvent=${SOLVENT:-implicit}
mkdir -p "$out"
echo "# capsid_table1.sh: e $energies; seeds $seeds; $steps steps; $capsomers capsomers, particle_fraction 0.033, solvent $solvent; $(run_stamp)"
commit_line
for e in $energies; do
  for seed in $seeds; do
    dir="$out/e${e}_seed$seed"
    [ -f "$dir/summary.json" ] && continue
    start_or_resume "$dir" capsid-assembly --set capsomers="$capsomers" --set particle_fraction=0.033 \
      --set solvent="$solvent" --set start=monomers --set attraction="$e" --set seed="$seed" \
      --set steps="$steps" --set sample_every=$((steps / 50)) --set progress_interval=0
    "$exe" run "${run_args[@]}" -o "$dir" >/dev/null
  done
done
/usr/bin/python3 - "$out" "$energies" "$seeds" <<'PY'
import json, sys
out, energies, seeds = sys.argv[1], sys.argv[2].split(), sys.argv[3].split()
print("| e | seed | largest | monomers | 2-5 | 6-50 | 51-59 | 60 | shells | bonds | wall s |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for e in energies:
    for seed in seeds:
        s = json.load(open(f"{out}/e{e}_seed{seed}/summary.json"))
        m = s["scene_measures"]
        f = m["mass_fractions"]
        print(f"| {e} | {seed} | {m['largest_cluster']:.0f} | " + " | ".join(f"{x:.3f}" for x in f)
              + f" | {m['complete_shells']:.0f} | {m['bonds']:.0f} | {s['wall_seconds']:.0f} |")
# How soon: the first sample with mass in clusters of 6 or more (the lag), and the first at which
# that mass reaches half its value at the end (samples every 1/50 of the run).
import numpy as np
sys.path.insert(0, "scripts")
from emergentpy import Run  # a continued run's segments read as one
print()
print("| e | seed | first mass in 6+ (tau) | half of the final mass in 6+ (tau) |")
print("|---|---|---|---|")
for e in energies:
    for seed in seeds:
        t, fractions = Run(f"{out}/e{e}_seed{seed}").observable("mass_fractions")
        t = np.asarray(t, float).reshape(-1)
        big = np.asarray(fractions, float).reshape(len(t), -1)[:, 2:].sum(axis=1)
        first = f"{t[np.argmax(big > 0)]:.0f}" if (big > 0).any() else "-"
        half = f"{t[np.argmax(big >= 0.5 * big[-1])]:.0f}" if big[-1] > 0 else "-"
        print(f"| {e} | {seed} | {first} | {half} |")
PY

#!/usr/bin/env bash
# capsid-assembly growth-step probabilities (the paper: at e = 0.09 a dimer grows to a trimer
# with ~1 % probability, a trimer to a tetramer ~50 %, each step from 4 to 50 ~60 %): for each
# seeded size n (start=cluster, a compact patch of the closed shell plus monomers; n = 1 means
# start=monomers), runs the implicit solvent (or SOLVENT) at the given attraction and sums the
# scene's event tallies over seeds: a cluster of n that has n + 1 members at the next sample
# grew, n - 1 shrank; P_n = grew / (grew + shrank) is the chance that a change of size is
# growth. The same trajectories are also tallied from every second sample (twice the interval):
# the probabilities must not change when the interval is halved. Monomer runs use
# MONOMER_CAPSOMERS (more dimers).
# usage: benchmarks/capsid_growth_steps.sh [OUT] [SIZES...]   (defaults /tmp/capsid_growth;
#        sizes 1 2 3 4 6 8 12 16 20 25 30 35 40 45 50 55); E (0.09), SEEDS ("41 42"), STEPS
#        (100000), SAMPLE (25 steps), CAPSOMERS (120), MONOMER_CAPSOMERS (300), SOLVENT
#        (implicit), PARTICLE_FRACTION (0.022), DT (the scene's 0.005) and SET ("key=value
#        ...": more scene settings, e.g. the site rows "site_depth_outer=0") override. Runs
#        already complete in OUT are kept (one OUT per setting); the table goes to stdout.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-/tmp/capsid_growth}
shift || true
sizes=${*:-1 2 3 4 6 8 12 16 20 25 30 35 40 45 50 55}
. benchmarks/common.sh
e=${E:-0.09}
seeds=${SEEDS:-"41 42"}
steps=${STEPS:-100000}
sample=${SAMPLE:-25}
capsomers=${CAPSOMERS:-120}
monomer_capsomers=${MONOMER_CAPSOMERS:-300}
solvent=${SOLVENT:-implicit}
fraction=${PARTICLE_FRACTION:-0.022}
extra=()
[ -n "${DT:-}" ] && extra+=(--set dt="$DT")
for kv in ${SET:-}; do extra+=(--set "$kv"); done
mkdir -p "$out"
echo "# capsid_growth_steps.sh: e $e; sizes $sizes; seeds $seeds; $steps steps, sample every $sample; $capsomers capsomers ($monomer_capsomers from monomers), particle_fraction $fraction, solvent $solvent${SET:+, $SET}${DT:+, dt $DT}; $(run_stamp)"
commit_line
for n in $sizes; do
  for seed in $seeds; do
    file="$out/n${n}_seed$seed.json"
    [ -f "$file" ] && continue
    if [ "$n" = 1 ]; then start=(--set start=monomers --set capsomers="$monomer_capsomers")
    else start=(--set start=cluster --set cluster_size="$n" --set capsomers="$capsomers"); fi
    "$exe" run capsid-assembly "${extra[@]}" "${start[@]}" --set particle_fraction="$fraction" --set solvent="$solvent" --set attraction="$e" \
      --set seed="$seed" --set steps="$steps" --set sample_every="$sample" \
      --set progress_interval=0 --summary-json "$file.tmp" >/dev/null
    mv "$file.tmp" "$file"
  done
done
/usr/bin/python3 - "$out" "$sizes" "$seeds" "$sample" <<'PY'
import json, sys
sys.path.insert(0, "scripts")
from emergentpy import wilson_interval as wilson
out, sizes, seeds, sample = sys.argv[1], sys.argv[2].split(), sys.argv[3].split(), int(sys.argv[4])
# Tallies by origin: the monomer runs (dimers formed by chance encounters) and the seeded runs
# (whose small clusters are mostly the seed's fragments, their lost member still nearby);
# "fine" every sample, "coarse" every second.
def zero():
    return {t: [0] * 60 for t in ("fine", "coarse")}
grew = {"monomers": zero(), "seeded": zero(), "all": zero()}
shrank = {"monomers": zero(), "seeded": zero(), "all": zero()}
seen = {"monomers": zero(), "seeded": zero(), "all": zero()}
wall = 0.0
dts = set()
for n in sizes:
    for seed in seeds:
        s = json.load(open(f"{out}/n{n}_seed{seed}.json"))
        m = s["scene_measures"]
        wall += s["wall_seconds"]
        dts.add(s["dt"])
        for origin in ("monomers" if n == "1" else "seeded", "all"):
            for tally, suffix in (("fine", ""), ("coarse", "_coarse")):
                for k in range(60):
                    grew[origin][tally][k] += m["growth_events" + suffix][k]
                    shrank[origin][tally][k] += m["loss_events" + suffix][k]
                    seen[origin][tally][k] += m["clusters_seen" + suffix][k]

if len(dts) != 1:
    sys.exit(f"capsid_growth_steps: runs in {out} at different time steps {sorted(dts)}: one OUT per setting")
tau = dts.pop() * sample


def row(label, lo, hi, origin="all"):
    cells = [label]
    for tally in ("fine", "coarse"):
        g = sum(grew[origin][tally][k - 1] for k in range(lo, hi + 1))
        l = sum(shrank[origin][tally][k - 1] for k in range(lo, hi + 1))
        w = wilson(g, g + l)
        cells += [f"{g:.0f}", f"{l:.0f}", "-" if w is None else f"{w[0]:.3f} ({w[1]:.3f}-{w[2]:.3f})"]
    # How often a cluster of these sizes changes size (the kinetics, to compare solvents).
    seen_time = tau * sum(seen[origin]["fine"][k - 1] for k in range(lo, hi + 1))
    changes = sum(grew[origin]["fine"][k - 1] + shrank[origin]["fine"][k - 1] for k in range(lo, hi + 1))
    cells.append("-" if seen_time == 0 else f"{changes / seen_time:.3f}")
    print("| " + " | ".join(cells) + " |")


print(f"# growth events g, loss events l and P = g / (g + l) (95 % Wilson interval), tallied every "
      f"{sample} steps ({tau:g} tau) and every {2 * sample} ({2 * tau:g} tau) on the same runs; "
      f"total wall {wall:.0f} s")
print(f"| size n | g ({tau:g} tau) | l | P | g ({2 * tau:g} tau) | l | P | changes per cluster per tau |")
print("|---|---|---|---|---|---|---|---|")
row("2 (dimer -> trimer), from monomers", 2, 2, "monomers")
row("2, in the seeded runs", 2, 2, "seeded")
row("3 (trimer -> tetramer)", 3, 3)
for lo, hi in ((4, 10), (11, 20), (21, 30), (31, 40), (41, 50), (51, 59)):
    row(f"{lo}-{hi}", lo, hi)
row("4-50 (paper: ~0.6)", 4, 50)
mono = {t: x["monomers"]["fine"] for t, x in (("g", grew), ("l", shrank), ("s", seen))}
dimers = mono["g"][1] + mono["l"][1]
if dimers:
    print(f"# monomer runs: {mono['g'][0] / 2:.0f} dimers formed from two monomers (monomers that "
          f"grew, / 2), {dimers:.0f} ended (grew or broke), mean dimer lifetime "
          f"{tau * mono['s'][1] / dimers:.2f} tau (sampled time as a dimer / dimers ended)")
print("# per size (fine tally, all runs): n seen grew shrank")
for k in range(1, 60):
    g, l = grew["all"]["fine"][k], shrank["all"]["fine"][k]
    if g + l > 0 or k + 1 in (2, 3):
        print(f"# {k + 1} {seen['all']['fine'][k]:.0f} {g:.0f} {l:.0f}")
PY

#!/usr/bin/env bash
# capsid-assembly seeded completion: how long an open 59-cluster (the closed shell less one
# capsomer) takes to insert its last particle from the surrounding monomers. Runs the `small`
# preset (60 capsomers in explicit solvent, start=open_shell) at the given attraction for each
# seed, samples the bond census every SAMPLE steps, and tabulates the first sampled time with a
# complete shell (censored at the run's end when none formed), then the rate of completion
# (exponential waiting, exact Poisson interval) and the distribution: the Kaplan-Meier fraction
# still open at each completion beside the exponential's.
# usage: benchmarks/capsid_completion.sh [ATTRACTION] [OUT]   (defaults: 0.09, the calibrated
#        default, and /tmp/capsid_completion, big files); SEEDS overrides "11 12 13 14 15 16",
#        STEPS the run length (1e5), SAMPLE the sample interval (500), SETS further settings
#        (e.g. "solvent=implicit capsomers=120": more monomers around the gap). Runs already
#        complete in OUT are kept (use one OUT per SETS), stopped ones continued from their
#        checkpoints; the table goes to stdout.
set -euo pipefail
cd "$(dirname "$0")/.."
e=${1:-0.09}
out=${2:-/tmp/capsid_completion}
. benchmarks/common.sh
mkdir -p "$out"
seeds=${SEEDS:-"11 12 13 14 15 16"}
steps=${STEPS:-100000}
sample=${SAMPLE:-500}
sets=()
for kv in ${SETS:-}; do sets+=(--set "$kv"); done
echo "# capsid_completion.sh $e; steps $steps, sample every $sample; sets: ${SETS:-none}; $(run_stamp)"
commit_line
for seed in $seeds; do
  dir="$out/e${e}_seed$seed"
  [ -f "$dir/summary.json" ] && continue
  start_or_resume "$dir" capsid-assembly --preset small --set start=open_shell --set attraction="$e" \
    --set seed="$seed" --set steps="$steps" --set sample_every="$sample" \
    --set progress_interval=0 "${sets[@]}"
  "$exe" run "${run_args[@]}" -o "$dir" >/dev/null
done
/usr/bin/python3 - "$out" "$e" $seeds <<'PY'
import json, sys
sys.path.insert(0, "scripts")
from emergentpy import Run  # a continued run's segments read as one
out, e, seeds = sys.argv[1], sys.argv[2], sys.argv[3:]
print("# seed  completed_at_tau  largest_at_end  shells_at_end  wall_s")
done, censored = [], []
for seed in seeds:
    d = f"{out}/e{e}_seed{seed}"
    s = json.load(open(f"{d}/summary.json"))
    t, shells = Run(d).observable("complete_shells")
    first = next((float(ti) for ti, n in zip(t, shells) if n >= 1), None)
    m = s["scene_measures"]
    (done if first is not None else censored).append(first if first is not None else float(t[-1]))
    print(f"{seed:5s}  {('%.1f' % first) if first is not None else ('>%.0f' % t[-1]):>16s}"
          f"  {m['largest_cluster']:14.0f}  {m['complete_shells']:13.0f}  {s['wall_seconds']:6.0f}")
# Completion as a rate (exponential waiting times, censored runs counted): k completions in
# the total observed time T give the rate k / T, the median time ln 2 T / k, and the exact
# Poisson 95 % interval of k / T bounds both.
import math
def poisson_cdf(k, mu):
    return sum(math.exp(-mu) * mu ** j / math.factorial(j) for j in range(k + 1))
def solve(f, lo, hi):
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(mid) > 0 else (lo, mid)
    return 0.5 * (lo + hi)
k, T = len(done), sum(done) + sum(censored)
upper = solve(lambda mu: poisson_cdf(k, mu) - 0.025, 0.0, 100.0 + 10 * k)
lower = solve(lambda mu: poisson_cdf(k - 1, mu) - 0.975, 0.0, 100.0 + 10 * k) if k > 0 else 0.0
print(f"# completed {k} of {len(seeds)}" + (f" (at {', '.join('%.0f' % t for t in sorted(done))} tau)" if done else "")
      + f"; {len(censored)} censored; total observed {T:.0f} tau")
print(f"# rate {k / T:.3g} per tau (95 %: {lower / T:.3g}-{upper / T:.3g}); median time to complete "
      + (f"{math.log(2) * T / k:.0f} tau" if k else "unbounded above") + f" (95 %: {math.log(2) * T / upper:.0f}-"
      + (f"{math.log(2) * T / lower:.0f}" if lower > 0 else "inf") + " tau)")
# The distribution itself: the Kaplan-Meier estimate of the fraction still open at each
# completion (censored runs leave the risk set at their end), beside the exponential
# exp(-rate t) that the rate above assumes.
if done:
    print("# t_tau  still_open  kaplan_meier  exponential")
    survival = 1.0
    for t in sorted(done):
        at_risk = sum(1 for x in done + censored if x >= t)
        survival *= 1 - 1 / at_risk
        print(f"{t:7.0f}  {at_risk:10d}  {survival:12.3f}  {math.exp(-k / T * t):11.3f}")
PY

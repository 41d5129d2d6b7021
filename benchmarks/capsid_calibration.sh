#!/usr/bin/env bash
# capsid-assembly: calibration of the attraction e against the paper's early state (8 dimers
# among 4752 capsomers after 5e4 steps at e = 0.09, p = 0.022, explicit solvent). Runs a box of
# CAPSOMERS capsomers at the paper's p and density (the same concentration) from monomers for
# 5e4 steps, for each e and seed, JOBS runs at a time (one rank each), and tabulates the dimers
# at step 5e4 scaled to 4752 capsomers, with the mean dimer count over steps 25000..50000
# (sampled every 1000, same scaling) as a steadier estimate.
# usage: benchmarks/capsid_calibration.sh [CAPSOMERS] [JOBS] [OUT]
#        (defaults 594 = 4752/8, 2, benchmarks/logs/capsid_calibration); E_VALUES and SEEDS
#        (space-separated) override "0.08 0.09 0.10 0.11" and "1 2 3"; SET="key=value ..." adds
#        scene settings (e.g. SET="site_depth_outer=0.25", another site row). Runs already
#        complete in OUT are kept, stopped ones continued from their checkpoints; the table goes
#        to stdout (save it as the log).
set -euo pipefail
cd "$(dirname "$0")/.."
capsomers=${1:-594}
jobs=${2:-2}
out=${3:-benchmarks/logs/capsid_calibration}
case $capsomers in ''|*[!0-9]*|0) echo "capsid_calibration.sh: CAPSOMERS='$capsomers' must be a positive integer" >&2; exit 2 ;; esac
case $jobs in ''|*[!0-9]*|0) echo "capsid_calibration.sh: JOBS='$jobs' must be a positive integer" >&2; exit 2 ;; esac
. benchmarks/common.sh
mkdir -p "$out"
e_values=${E_VALUES:-"0.08 0.09 0.10 0.11"}
seeds=${SEEDS:-"1 2 3"}
extra=()
for kv in ${SET:-}; do extra+=(--set "$kv"); done
echo "# capsid_calibration.sh $capsomers capsomers, $jobs jobs${SET:+; SET=\"$SET\"}; $(run_stamp)"
commit_line
one() {
  local e=$1 seed=$2 dir="$out/e${1}_seed$2"
  [ -f "$dir/summary.json" ] && return 0
  start_or_resume "$dir" capsid-assembly "${extra[@]}" --set capsomers="$capsomers" --set attraction="$e" \
    --set seed="$seed" --set start=monomers --set steps=50000 --set sample_every=1000 --set progress_interval=0
  "$exe" run "${run_args[@]}" -o "$dir" >/dev/null
}
running=0
for e in $e_values; do
  for seed in $seeds; do
    one "$e" "$seed" &
    running=$((running + 1))
    if [ $running -ge "$jobs" ]; then wait -n; running=$((running - 1)); fi
  done
done
wait
/usr/bin/python3 - "$out" "$capsomers" $e_values <<'PY'
import json, os, sys
import h5py, numpy as np
sys.path.insert(0, "scripts")
from emergentpy import Run
out, n, es = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
def dimers(run):
    """(step, value) of the dimer census over a run and its continuations; a step that two
    segments hold (a run killed after its last checkpoint, continued from it) counted once."""
    steps, values = [], []
    for path in Run(run).trajectory_paths:
        with h5py.File(path, "r") as f:
            if "dimers" in f["observables"]:
                steps.append(f["observables/dimers/step"][:])
                values.append(f["observables/dimers/value"][:].ravel())
    step, first = np.unique(np.concatenate(steps), return_index=True)
    return step, np.concatenate(values)[first]
scale = 4752 / n
print(f"# dimers scaled to 4752 capsomers (x {scale:g}); paper: 8 (+- 2.8, Poisson) at step 50000, e = 0.09")
print("# e      seed  dimers@5e4  mean(25k..50k)  largest  wall_s")
for e in es:
    snap, late = [], []
    for d in sorted(x for x in os.listdir(out) if x.startswith(f"e{e}_seed")):
        s = json.load(open(f"{out}/{d}/summary.json"))
        step, value = dimers(f"{out}/{d}")
        at = value[step == 50000][0] * scale
        mean = value[step >= 25000].mean() * scale
        snap.append(at); late.append(mean)
        print(f"{e:6s}  {d.split('seed')[1]:4s}  {at:10.1f}  {mean:14.2f}  {s['scene_measures']['largest_cluster']:7.0f}  {s['wall_seconds']:6.0f}")
    if snap:
        print(f"{e:6s}  mean  {np.mean(snap):10.1f}  {np.mean(late):14.2f}   (+- {np.std(late, ddof=1) / np.sqrt(len(late)) if len(late) > 1 else float('nan'):.2f} over seeds)")
PY

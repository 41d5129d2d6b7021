#!/usr/bin/env bash
# How often the capsid census misses a closed cage when closure is judged by bonds alone
# (contact_range = bond_range = 0.5) against face contacts (contact_range 1.0, the default):
# the same continuation of a checkpoint twice, analysis only differing (same trajectory), with
# a census every SAMPLE steps (25), STEPS steps (20000) on one rank; per sample, the census's
# complete shells against its clusters of 60 members, and the closed cages by size.
# usage: benchmarks/capsid_contact_range.sh CHECKPOINT
#   e.g. benchmarks/logs/capsid_long/d025_p0.022_e0.12_seed21/checkpoint.h5 (two shells and a
#   24-cage at 180100 tau, implicit solvent)
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -eq 1 ] || { sed -n 2,9p "$0"; exit 2; }
. benchmarks/common.sh
checkpoint=$(realpath "$1")
steps=${STEPS:-20000} sample=${SAMPLE:-25}
start=$(/usr/bin/python3 -c "import h5py; print(int(h5py.File('$checkpoint', 'r')['checkpoint'].attrs['step']))")
echo "# $(date -u +%F) $(git rev-parse --short HEAD); $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')"
echo "# checkpoint $1 at step $start; $steps steps, a sample every $sample"
for range in 0.5 1.0; do
  mkdir -p "$work/cr$range"
  cp "$checkpoint" "$work/cr$range/checkpoint.h5"
  "$exe" run --restart "$work/cr$range/checkpoint.h5" -o "$work/cr$range" --set steps=$((start + steps)) \
    --set sample_every="$sample" --set contact_range="$range" --set output.every=0 \
    --set progress_interval=0 | tail -1
done
/usr/bin/python3 - "$work" <<'EOF'
import sys
sys.path.insert(0, "scripts")
import numpy as np
from emergentpy import Run
work = sys.argv[1]
print("| contact_range | samples | clusters of 60 (mean) | complete_shells (mean) | samples missing a shell | closed cages seen (members: share of samples) |")
print("|---|---|---|---|---|---|")
for r in ("0.5", "1.0"):
    run = Run(f"{work}/cr{r}")
    t, shells = run.observable("complete_shells")
    _, by_size = run.observable("clusters_by_size")
    _, closed = run.observable("closed_by_size")
    n60 = by_size[:, 59]
    seen = ", ".join(f"{n + 1}: {np.mean(closed[:, n] > 0):.3f}" for n in np.nonzero(closed.sum(0))[0])
    print(f"| {r} | {len(t)} | {n60.mean():.3f} | {shells.mean():.3f} | {int((shells < n60).sum())} | {seen or '-'} |")
EOF

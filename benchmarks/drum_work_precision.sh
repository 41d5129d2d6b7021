#!/usr/bin/env bash
# Work-precision of rotating-drum: wall time per revolution against the time step's effect on
# what the scene measures. A drum of D = 24, L = 16 with ~260 tetrahedra (the repose test's
# drum) turns 10 revolutions at each dt; the dynamic angle of repose (mean over revolutions
# 2-10, error from 4 blocks), the filled fraction and the largest contact overlap (as a fraction
# of the sphere diameter, sampled 10 times per revolution) are compared with the smallest dt. A dt at
# which the run stops (guards) is reported as such. REPEATS timed runs per dt (median). Draws
# PNG: each measure's difference from the smallest dt against the cost.
# usage: benchmarks/drum_work_precision.sh [REPEATS] [DTS] [PNG]
#        (defaults 3, "0.00125 0.0025 0.005 0.0075 0.01 0.015 0.02 0.03 0.04",
#         /tmp/emergent_drum_work_precision.png)
set -euo pipefail
cd "$(dirname "$0")/.."
repeats=${1:-3}
dts=${2:-"0.00125 0.0025 0.005 0.0075 0.01 0.015 0.02 0.03 0.04"}
png=${3:-/tmp/emergent_drum_work_precision.png}
. benchmarks/common.sh
drum=(--set diameter=24 --set length=16 --set bodies=260 --set progress_interval=0)
printf '| dt | steps/rev | wall s/rev (1 rank) | repose angle (deg) | fill | overlap (diameters): mean of sample max, largest | outcome |\n|---|---|---|---|---|---|---|\n'
for dt in $dts; do
  steps=$(awk -v dt="$dt" 'BEGIN { printf "%d", 10 * 6.283185307179586 / (0.2 * dt) + 0.5 }')
  every=$(awk -v s="$steps" 'BEGIN { printf "%d", s / 100 }')
  : >"$work/w$dt"
  outcome=ok
  for r in $(seq "$repeats"); do
    if ! "$exe" run rotating-drum "${drum[@]}" --set dt="$dt" --set steps="$steps" \
        --set sample_every="$every" -o "$work/d$dt" --overwrite >"$work/log" 2>&1; then
      outcome="stopped: $(grep -o 'error: .*' "$work/log" | head -1 | cut -c8-90)"
      break
    fi
    grep -o '"wall_seconds": [0-9.e+]*' "$work/d$dt/summary.json" | awk '{print $2 / 10}' >>"$work/w$dt"
  done
  if [ "$outcome" != ok ]; then printf '| %s | %d | - | - | - | - | %s |\n' "$dt" "$((steps / 10))" "$outcome"; continue; fi
  /usr/bin/python3 - "$work/d$dt" "$dt" "$((steps / 10))" "$(median <"$work/w$dt")" "$work/points" <<'PY'
import sys
sys.path.insert(0, "scripts")
import numpy as np
from emergentpy import Run
run = Run(sys.argv[1])
_, rev = run.observable("revolutions")
_, angle = run.observable("repose_angle")
_, fill = run.observable("fill_fraction")
_, overlap = run.observable("max_overlap")
rev, angle, fill, overlap = rev.reshape(-1), angle.reshape(-1), fill.reshape(-1), overlap.reshape(-1)
keep = rev >= 2
blocks = np.array([b.mean() for b in np.array_split(angle[keep], 4)])
err = blocks.std(ddof=1) / np.sqrt(len(blocks))
print(f"| {sys.argv[2]} | {sys.argv[3]} | {float(sys.argv[4]):.2f} | {angle[keep].mean():.2f} +- {err:.2f} "
      f"| {fill[keep].mean():.4f} | {overlap[keep].mean():.3f}, {overlap[keep].max():.3f} | ok |")
with open(sys.argv[5], "a") as f:
    f.write(f"{sys.argv[2]} {sys.argv[4]} {angle[keep].mean()} {err} {fill[keep].mean()} {overlap[keep].mean()}\n")
PY
done
/usr/bin/python3 - "$work/points" "$png" <<'PY'
import sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
dt, wall, angle, err, fill, overlap = np.loadtxt(sys.argv[1], ndmin=2).T
ref = np.argmin(dt)
fig, (ax_a, ax_f) = plt.subplots(1, 2, figsize=(10, 4))
ax_a.errorbar(wall, angle - angle[ref], yerr=err, fmt="o-")
ax_a.set_ylabel("repose angle - angle at smallest dt (deg)")
ax_f.plot(wall, 100 * (fill / fill[ref] - 1), "o-", label="fill")
ax_f.plot(wall, 100 * (overlap / overlap[ref] - 1), "s-", label="mean largest overlap")
ax_f.set_ylabel("difference from smallest dt (%)")
ax_f.legend()
for ax in (ax_a, ax_f):
    ax.set_xscale("log")
    ax.set_xlabel("wall seconds per revolution (1 rank)")
    ax.axhline(0, color="grey", lw=0.5)
    for x, y, d in zip(wall, (angle - angle[ref]) if ax is ax_a else 100 * (fill / fill[ref] - 1), dt):
        ax.annotate(f"{d:g}", (x, y), fontsize=7, textcoords="offset points", xytext=(3, 3))
fig.suptitle("rotating-drum: work-precision over dt (labels: dt)")
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=110)
print(f"\nfigure: {sys.argv[2]}")
PY

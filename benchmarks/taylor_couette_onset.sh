#!/usr/bin/env bash
# Onset of Taylor vortices: the `small` geometry (r_i 50, d 25, L 100, quadrant) run at several
# inner-cylinder speeds omega; for each, the amplitude of the dominant axial mode of v_r at
# mid-gap over the last quarter of the run against its start (noise). Near a supercritical
# onset A^2 grows linearly with Re - Re_c, so a line through A^2 of the runs above onset gives
# Re_c, compared with the linear-stability 76.3 (eta = 2/3). Re = omega r_i d / nu with the
# nu measured by planar-couette at the omega = 0.1 run's mid-gap state (1.156, RESULTS.md); the
# fluid's state, hence nu, shifts with omega (viscous heating), which this estimate ignores.
# Runs already complete in OUT_DIR are reused. Writes a table and OUT_DIR/onset.png.
# usage: benchmarks/taylor_couette_onset.sh [OUT_DIR] [OMEGAS] [STEPS] [RANKS]
#        (defaults /tmp/emergent_onset, "0.06 0.08 0.1", 100000, 2)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-/tmp/emergent_onset}
omegas=${2:-"0.06 0.08 0.1"}
steps=${3:-100000}
ranks=${4:-2}
source benchmarks/common.sh
scene_sweep "$out" "$ranks" "$steps" omega $omegas -- taylor-couette --preset small
/usr/bin/python3 - "$out" $omegas <<'PY'
import os, sys
sys.path.insert(0, "scripts")
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from emergentpy import Run
out, omegas = sys.argv[1], [float(w) for w in sys.argv[2:]]
nu, r_i, d, re_c_theory = 1.156, 50.0, 25.0, 76.3
rows = []
for w in omegas:
    run = Run(os.path.join(out, f"omega_{w:g}"))
    t, mode = run.observable("axial_mode")
    mode = mode.reshape(len(t), -1)
    amp = mode[:, 2]
    last = amp[-max(1, len(amp) // 4):]
    rows.append((w, w * r_i * d / nu, amp[0], last.mean(), last.std(), int(mode[-1, 0])))
print("| omega | Re | amplitude at start | amplitude, last quarter | mode m |")
print("|---|---|---|---|---|")
for w, re, a0, a, sa, m in rows:
    print(f"| {w:g} | {re:.1f} | {a0:.3f} | {a:.3f} +- {sa:.3f} | {m} |")
# Above onset: amplitude beyond 3x its start (noise).
above = [(re, a) for w, re, a0, a, sa, m in rows if a > 3 * a0]
if len(above) >= 2:
    re_, a_ = np.array(above).T
    slope, icpt = np.polyfit(re_, a_ ** 2, 1)
    re_c = -icpt / slope
    print(f"\nline through A^2 of {len(above)} runs above onset: Re_c = {re_c:.1f} "
          f"(linear stability {re_c_theory}, {100 * (re_c / re_c_theory - 1):+.0f} %)")
else:
    re_c = None
    print(f"\nfewer than two runs above onset: no Re_c estimate")
fig, ax = plt.subplots(figsize=(6, 4))
res = np.array([r[1] for r in rows])
ax.errorbar(res, [r[3] ** 2 for r in rows], yerr=[2 * r[3] * r[4] for r in rows], fmt="o",
            label="A^2, last quarter of each run")
ax.plot(res, [r[2] ** 2 for r in rows], "x", label="A^2 at the start (noise)")
if re_c is not None:
    x = np.linspace(min(re_c, res.min()), res.max(), 50)
    ax.plot(x, slope * x + icpt, "--", label=f"line: Re_c = {re_c:.1f}")
ax.axvline(re_c_theory, color="k", lw=0.8, label="linear stability 76.3")
ax.set_xlabel("Re = omega r_i d / nu")
ax.set_ylabel("dominant axial mode amplitude^2")
ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig(os.path.join(out, "onset.png"), dpi=120)
PY

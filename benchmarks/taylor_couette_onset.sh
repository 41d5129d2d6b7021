#!/usr/bin/env bash
# Onset of Taylor vortices: the `small` geometry (r_i 50, d 25, L 100, quadrant) run at several
# inner-cylinder speeds omega; for each, the amplitude of the dominant axial mode of v_r at
# mid-gap over the last quarter of the run against its start (noise). Near a supercritical
# onset A^2 grows linearly with Re - Re_c, so a line through A^2 of the runs above onset gives
# Re_c, compared with linear stability (emergent-couette-stability: 76.31 at eta = 2/3). A
# second estimate needs no saturation: the growth rate of the rolls while small (against linear
# theory's for the same mode at the run's Re), which is linear in Re near onset, and where a
# line through it crosses zero. Re = omega r_i d / nu with the
# nu measured by planar-couette at the omega = 0.1 run's mid-gap state (1.156, benchmarks/results/viscosity.md); the
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
# Each omega from the start: the preset's stepped start (a hold at 0.07) is switched off.
scene_sweep "$out" "$ranks" "$steps" omega $omegas -- taylor-couette --preset small --set spin_up_time=0
/usr/bin/python3 - "$out" $omegas <<'PY'
import os, sys
sys.path.insert(0, "scripts")
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import re as regex
import subprocess
import numpy as np
from emergentpy import Run, exponential_growth
out, omegas = sys.argv[1], [float(w) for w in sys.argv[2:]]
nu, r_i, d = 1.156, 50.0, 25.0


def linear_stability(reynolds):
    """Re_c and the growth rate (nu/d^2) of each mode m the tool lists at this Re."""
    text = subprocess.run(["build/bin/emergent-couette-stability", "--reynolds", f"{reynolds}"],
                          capture_output=True, text=True, check=True).stdout
    re_c = float(regex.search(r"Re_c = (\S+),", text).group(1))
    sigma = {int(a): float(b) for a, b in regex.findall(r"m = (\d+): .*sigma = (\S+)", text)}
    return re_c, sigma


re_c_theory = linear_stability(0)[0]
rows = []
for w in omegas:
    run = Run(os.path.join(out, f"omega_{w:g}"))
    t, mode = run.observable("axial_mode")
    mode = mode.reshape(len(t), -1)
    amp = mode[:, 2]
    last = amp[-max(1, len(amp) // 4):]
    re = w * r_i * d / nu
    # Growth while small, against linear theory's rate for the mode that grew.
    rate, used = exponential_growth(t, amp)
    m_grew = int(mode[used[-1], 0]) if rate is not None else 0
    theory = linear_stability(re)[1].get(m_grew) if rate is not None else None
    rows.append((w, re, amp[0], last.mean(), last.std(), int(mode[-1, 0]),
                 None if rate is None else rate * d * d / nu, m_grew, theory))
print("| omega | Re | amplitude at start | amplitude, last quarter | mode m | growth rate (nu/d^2), "
      "mode | linear theory at Re |")
print("|---|---|---|---|---|---|---|")
for w, re, a0, a, sa, m, rate, m_grew, theory in rows:
    grew = "-" if rate is None else f"{rate:.2f} (m = {m_grew})"
    th = "-" if theory is None else f"{theory:.2f}"
    print(f"| {w:g} | {re:.1f} | {a0:.3f} | {a:.3f} +- {sa:.3f} | {m} | {grew} | {th} |")
# A second estimate that needs no saturation: the measured growth rate is linear in Re near
# onset; where a line through it crosses zero.
grown = [(r[1], r[6]) for r in rows if r[6] is not None]
if len(grown) >= 2:
    g_re, g_rate = np.array(grown).T
    gs, gi = np.polyfit(g_re, g_rate, 1)
    print(f"\nline through the growth rates of {len(grown)} runs: zero at Re = {-gi / gs:.1f}")
# Above onset: amplitude beyond 3x its start (noise).
above = [(r[1], r[3]) for r in rows if r[3] > 3 * r[2]]
if len(above) >= 2:
    re_, a_ = np.array(above).T
    slope, icpt = np.polyfit(re_, a_ ** 2, 1)
    re_c = -icpt / slope
    print(f"\nline through A^2 of {len(above)} runs above onset: Re_c = {re_c:.1f} "
          f"(linear stability {re_c_theory:.2f}, {100 * (re_c / re_c_theory - 1):+.0f} %)")
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
ax.axvline(re_c_theory, color="k", lw=0.8, label=f"linear stability {re_c_theory:.1f}")
ax.set_xlabel("Re = omega r_i d / nu")
ax.set_ylabel("dominant axial mode amplitude^2")
ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig(os.path.join(out, "onset.png"), dpi=120)
PY

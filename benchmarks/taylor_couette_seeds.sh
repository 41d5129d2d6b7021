#!/usr/bin/env bash
# How many Taylor vortices the `small` system settles to: the same run from several seeds.
# With L = 4 d and elastic end caps, 4 vortices (lambda = 2 d, the linear-stability wavelength,
# the paper's count) and 5 (lambda = 1.6 d) both fit; which one a run picks is decided while the
# rolls grow out of noise, so only a count over seeds says how often each appears. For each
# seed: the vortex census over the last quarter of the run (most common count), the dominant
# axial cosine mode m of v_r at mid-gap (wavelength 2 L / m) and its amplitude, the history of
# the dominant mode, and the growth rate of the rolls while they are small (compare with
# build/bin/emergent-couette-stability --reynolds RE); OUT_DIR/seeds.png draws amplitude and
# mode against time, OUT_DIR/modes.png the 4- and 5-vortex modes alone.
# Runs already complete in OUT_DIR are reused.
# The preset's own schedule is a stepped start (held at omega 0.07, Re ~82, for 1750 tau, then
# 0.1 for 350 tau: STEPS 420000); further arguments go to the scene, e.g. the sudden start at 0.1:
# --set spin_up_time=0 (with STEPS 80000-150000 and NU=1.156). Growth rates are also given for
# the 4- and 5-vortex modes alone (their cosine amplitudes), in units of nu/d^2 with nu from the
# environment variable NU (default 1.07, the mid-gap state of the omega = 0.07 hold, where the
# stepped start's rolls grow; the omega = 0.1 state: 1.156; one nu for the whole run, so a rate
# fitted after a step is in the other state's units).
# usage: [NU=nu] benchmarks/taylor_couette_seeds.sh [OUT_DIR] [SEEDS] [STEPS] [RANKS] [SCENE_ARGS...]
#        (defaults /tmp/emergent_tc_seeds, "1 2 3 4 5 6", 420000 = 2100 tau (the preset), 2)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-/tmp/emergent_tc_seeds}
seeds=${2:-"1 2 3 4 5 6"}
steps=${3:-420000}
ranks=${4:-2}
shift $(( $# < 4 ? $# : 4 ))
source benchmarks/common.sh
scene_sweep "$out" "$ranks" "$steps" seed $seeds -- taylor-couette --preset small "$@"
/usr/bin/python3 - "$out" $seeds <<'PY'
import collections, os, sys
sys.path.insert(0, "scripts")
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from emergentpy import Run, cosine_modes, exponential_growth
out, seeds = sys.argv[1], sys.argv[2:]
length, gap = 100.0, 25.0  # the small preset
nu = float(os.environ.get("NU", "1.07"))  # measured at the mid-gap state of the growth
print(f"(growth rates in nu/d^2 with nu = {nu})\n")
print("| seed | vortices, last quarter (most common, range) | dominant mode m over time | "
      "wavelength / d (end) | amplitude (end) | growth rate, A in 0.03-0.15 | m = 4 alone | m = 5 alone |")
print("|---|---|---|---|---|---|---|---|")
tally = collections.Counter()
fig, (ax_a, ax_m) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
fig_modes, ax_modes = plt.subplots(figsize=(7, 4))
for s in seeds:
    run = Run(os.path.join(out, f"seed_{s}"))
    t, count = run.observable("vortex_count")
    count = count.reshape(-1).astype(int)
    last = count[-max(1, len(count) // 4):]
    common = collections.Counter(last).most_common(1)[0][0]
    tally[common] += 1
    tm, mode = run.observable("axial_mode")
    mode = mode.reshape(len(tm), -1)
    m, amp = mode[:, 0].astype(int), mode[:, 2]
    # History of the dominant mode: each change with the time it happened.
    history = [f"{m[0]}"] + [f"{m[i]} (t={tm[i]:.0f})" for i in range(1, len(m)) if m[i] != m[i - 1]]
    # Linear growth while A is well above the noise (~0.01) and well below saturation (~0.45).
    slope, sel = exponential_growth(tm, amp)
    rate = "n/a" if slope is None else f"{slope * gap**2 / nu:.1f} (m = {m[sel[-1]]}, {len(sel)} frames)"
    tv, profile = run.observable("radial_velocity_midgap")
    alone = []
    for k, a in cosine_modes(profile.reshape(len(tv), -1), (4, 5)).items():
        line = "-" if k == 4 else ":"
        ax_modes.semilogy(tv, a, line, color=f"C{seeds.index(s)}", label=f"seed {s}, m = {k}")
        r, used = exponential_growth(tv, a)
        alone.append("n/a" if r is None else f"{r * gap**2 / nu:.2f} (t {tv[used[0]]:.0f}-{tv[used[-1]]:.0f})")
    wavelength = 2 * length / m[-1] / gap if m[-1] > 0 else float("nan")
    ax_a.semilogy(tm, amp, "o-", ms=3, label=f"seed {s}: {common} vortices")
    ax_m.step(tm, m, where="post")
    print(f"| {s} | {common} ({last.min()}-{last.max()}) | {' -> '.join(history)} | "
          f"{wavelength:.2f} | {amp[-1]:.3f} | {rate} | {alone[0]} | {alone[1]} |")
print("\nvortex counts over seeds: " + ", ".join(f"{k}: {v}" for k, v in sorted(tally.items())))
ax_a.set_ylabel("amplitude of the dominant mode")
ax_a.legend(fontsize=8)
ax_m.set_ylabel("dominant mode m (vortices)")
ax_m.set_ylim(0, 10)
ax_m.set_xlabel("t (tau)")
fig.suptitle("taylor-couette small: the pattern chosen from noise, by seed")
fig.tight_layout()
fig.savefig(os.path.join(out, "seeds.png"), dpi=110)
ax_modes.set_xlabel("t (tau)")
ax_modes.set_ylabel("amplitude of the mode alone")
ax_modes.set_title("4 vortices (solid) against 5 (dotted), by seed")
ax_modes.legend(fontsize=7, ncol=2)
fig_modes.tight_layout()
fig_modes.savefig(os.path.join(out, "modes.png"), dpi=110)
print(f"figures: {os.path.join(out, 'seeds.png')}, {os.path.join(out, 'modes.png')}")
PY

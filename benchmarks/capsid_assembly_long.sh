#!/usr/bin/env bash
# capsid-assembly from monomers over as long as a machine allows: one run per (e, seed) in the
# implicit solvent at Table 1's particle fraction, checkpointed, stopped whenever needed and
# continued later. Its growth and loss tallies come from cluster censuses every EVENTS steps
# between the samples (events_every), so they count the clusters met during assembly (the
# paper's growth-step probabilities, not seeded patches), at that interval and at twice it.
# usage:
#   benchmarks/capsid_assembly_long.sh run OUT E SEED        starts OUT/e<E>_seed<SEED>, or
#       continues it from its checkpoint; runs until STEPS (1e8), then removes its checkpoint, or
#       until SIGUSR1/SIGTERM (a checkpoint
#       at the next step, exit status 5), so `kill -USR1` ends a session's share cleanly.
#       CAPSOMERS (300), PARTICLE_FRACTION (Table 1's 0.033), SOLVENT (implicit), DT (the scene's 0.005; the implicit solvent holds
#       to 0.02, benchmarks/results/capsid.md "A longer step in the implicit solvent"), SAMPLE (100 tau),
#       EVENTS (0.25 tau), CHECKPOINT (1000 tau) and FRAMES (5000 tau: between trajectory frames,
#       whose cluster ids scripts/capsid_cages fits) override, the last four in steps; SET="key=value
#       ..." adds scene settings (e.g. the site rows: SET="site_depth_outer=0"). DT on a
#       continuation changes the step from there on (and the intervals with it: the tallies
#       start afresh); ADJUST="key=value ..." changes adjustable settings of a continuation
#       (e.g. "skin=1.4", the faster list skin at DT=0.02).
#   benchmarks/capsid_assembly_long.sh table RUN_DIR...      mass fractions by size group at
#       every tenth of the run so far, the lag (first mass in clusters of 6 or more), the first
#       complete shell, the last sample, when the shells first held half the mass they hold
#       at the end (the paper's half-time; a lower bound while shells still come); and P_n = g / (g + l) by size from the tallies at the
#       last sample (since the events interval was last set), at the interval and twice it.
#   benchmarks/capsid_assembly_long.sh at TIME RUN_DIR...   one row per run at its last sample at
#       or before TIME tau: e, seed, mass fractions, largest, shells, clusters of 6+, the lag and the
#       first shell by then (Table 1 at equal run length); runs that have not reached TIME are
#       named below the table, and the exit status is then 3.
#   benchmarks/capsid_assembly_long.sh window RUN_DIR STEPS  copies RUN_DIR's checkpoint to
#       RUN_DIR/window<STEP> and continues it STEPS steps with censuses every WINDOW_EVENTS (25)
#       steps: the same table over a short stretch at a finer interval (a continuation at another
#       interval starts the tallies afresh; at the checkpoint's own interval they go on from it,
#       and the checkpoint's are subtracted: either way they are the window's own), and where the clusters
#       of each size come from: pieces shed by larger ones, monomers meeting, single steps up.
set -euo pipefail
cd "$(dirname "$0")/.."
. benchmarks/common.sh
what=${1:-}
shift || true
series_py='
import os, sys
sys.path.insert(0, "scripts")
import h5py, numpy as np
from emergentpy import Run, wilson_interval as wilson
def step_table(tally, interval, dt):
    """P_n = g / (g + l) by size group, from tallies (name -> 60 counts) at interval and twice it."""
    tau = dt * interval
    print(f"| size n | g ({tau:g} tau) | l | P | g ({2 * tau:g} tau) | l | P |")
    print("|---|---|---|---|---|---|---|")
    for lo, hi in ((2, 2), (3, 3), (4, 10), (11, 20), (21, 30), (31, 40), (41, 50), (51, 59), (4, 50)):
        cells = [f"{lo}" if lo == hi else f"{lo}-{hi}"]
        for suffix in ("", "_coarse"):
            g = sum(tally["growth_events" + suffix][k - 1] for k in range(lo, hi + 1))
            l = sum(tally["loss_events" + suffix][k - 1] for k in range(lo, hi + 1))
            w = wilson(g, g + l)
            cells += [f"{g:.0f}", f"{l:.0f}", "-" if w is None else f"{w[0]:.3f} ({w[1]:.3f}-{w[2]:.3f})"]
        print("| " + " | ".join(cells) + " |")
def piece_table(tally, interval, dt, span):
    """Where clusters of each size come from, per 1000 tau over span tau: pieces shed by larger
    clusters, clusters assembled from monomers alone, and (for 3+) single steps up from n - 1;
    and the clusters of each size that shed a piece or merged with a piece of another."""
    if "pieces_shed" not in tally:
        print("# (no piece tallies: a run from before they were counted)")
        return
    print(f"| size n | pieces of n shed ({dt * interval:g} tau) | assembled from monomers | grew from n - 1 "
          f"| clusters of n that split | merged | pieces shed ({2 * dt * interval:g} tau) | split | merged |")
    print("|---|---|---|---|---|---|---|---|---|")
    per = 1000.0 / span
    for lo, hi in ((2, 2), (3, 3), (4, 5), (6, 10), (11, 20), (21, 30), (31, 40), (41, 59), (2, 5), (6, 59)):
        r = lambda name, shift=0: per * sum(tally[name][k - 1 - shift] for k in range(lo, hi + 1))
        cells = [f"{lo}" if lo == hi else f"{lo}-{hi}"]
        values = [r("pieces_shed"), r("assembled_from_monomers"), r("growth_events", 1), r("split_events"),
                  r("merge_events"), r("pieces_shed_coarse"), r("split_events_coarse"), r("merge_events_coarse")]
        cells += [f"{v:.1f}" for v in values]
        print("| " + " | ".join(cells) + " |")
    print("# rates per 1000 tau; grew from n - 1 for n = 2 counts both monomers of each new dimer")
def series(run, name):
    """An observable over a run and its continuations (emergentpy reads them as one), as rows."""
    t, v = Run(run).observable(name)
    t = np.asarray(t, float).reshape(-1)
    return t, np.asarray(v, float).reshape(len(t), -1)
'
case "$what" in
run)
  [ $# -eq 3 ] || { echo "usage: $0 run OUT E SEED" >&2; exit 2; }
  dir="$1/e$2_seed$3"
  dt=${DT:-0.005}
  steps_for 1 "$dt" >/dev/null  # a DT that is not a number stops here, in one line
  steps_of() { steps_for "$1" "$dt"; }
  intervals=(--set sample_every="${SAMPLE:-$(steps_of 100)}" --set events_every="${EVENTS:-$(steps_of 0.25)}"
             --set output.every="${FRAMES:-$(steps_of 5000)}" --set checkpoint_every="${CHECKPOINT:-$(steps_of 1000)}")
  if [ -f "$dir/checkpoint.h5" ]; then
    [ -n "${DT:-}" ] || intervals=()
    for kv in ${ADJUST:-}; do intervals+=(--set "$kv"); done
    "$exe" run --restart "$dir/checkpoint.h5" ${DT:+--set dt="$DT"} "${intervals[@]}" -o "$dir" || exit
    rm -f "$dir/checkpoint.h5"  # the run has ended: nothing is kept to continue it
    exit 0
  fi
  extra=()
  for kv in ${SET:-}; do extra+=(--set "$kv"); done
  "$exe" run capsid-assembly "${extra[@]}" --set capsomers="${CAPSOMERS:-300}" --set particle_fraction="${PARTICLE_FRACTION:-0.033}" \
    --set solvent="${SOLVENT:-implicit}" --set start=monomers --set attraction="$2" --set seed="$3" \
    --set dt="$dt" --set steps="${STEPS:-100000000}" "${intervals[@]}" --set progress_interval=600 -o "$dir" || exit
  rm -f "$dir/checkpoint.h5"  # the run has ended: nothing is kept to continue it
  ;;
table)
  [ $# -ge 1 ] || { echo "usage: $0 table RUN_DIR..." >&2; exit 2; }
  /usr/bin/python3 - "$@" <<PY
import sys
$series_py
for run in sys.argv[1:]:
    t, m = series(run, "mass_fractions")
    _, big = series(run, "largest_cluster")
    _, shells = series(run, "complete_shells")
    # Clusters of 6+ at each sample, where the run counted them (clusters_by_size; older runs did not).
    try:
        tn, by_size = series(run, "clusters_by_size")
        nuclei = dict(zip(np.round(tn, 6), by_size[:, 5:].sum(axis=1)))
    except KeyError:
        nuclei = {}
    print(f"## {run}: {len(t)} samples to t = {t[-1]:.0f} tau")
    print("| t (tau) | monomers | 2-5 | 6-50 | 51-59 | 60 | largest | shells | clusters of 6+ |")
    print("|---|---|---|---|---|---|---|---|---|")
    picks = sorted(set([int(round(k * (len(t) - 1) / 10)) for k in range(11)]))
    for k in picks:
        n6 = nuclei.get(round(t[k], 6))
        print(f"| {t[k]:.0f} | " + " | ".join(f"{x:.3f}" for x in m[k]) + f" | {big[k, 0]:.0f} | {shells[k, 0]:.0f} | "
              + ("-" if n6 is None else f"{n6:.0f}") + " |")
    six = m[:, 2:].sum(axis=1)
    lag = f"{t[np.argmax(six > 0)]:.0f} tau" if (six > 0).any() else "none yet"
    first_shell = f"{t[np.argmax(shells[:, 0] > 0)]:.0f} tau" if (shells[:, 0] > 0).any() else "none yet"
    print(f"# lag (first mass in clusters of 6+): {lag}; first complete shell: {first_shell}; "
          f"largest cluster ever sampled: {big[:, 0].max():.0f}")
    # The paper's half-time: when the shells first held half the mass they hold at the end. While
    # a run still adds shells this is a lower bound of the final one.
    shell_mass = m[:, 4]
    if shell_mass[-1] > 0:
        half = t[np.argmax(shell_mass >= 0.5 * shell_mass[-1])]
        print(f"# mass in complete shells at the end: {shell_mass[-1]:.3f}; half of it first at {half:g} tau")
    # The tallies' interval: the latest segment's events_every (0: the samples'); a run that
    # ended has no checkpoint left.
    cfg = Run(run).parameters()
    interval = int(cfg["events_every"]) if int(cfg.get("events_every", 0)) > 0 else int(cfg["sample_every"])
    dt = float(cfg["dt"])
    tally = {n: series(run, n)[1][-1] for n in ("growth_events", "loss_events", "growth_events_coarse", "loss_events_coarse")}
    print(f"# growth steps from the tallies at the last sample (censuses every {interval} steps of {dt:g} since that interval was set):")
    step_table(tally, interval, dt)
PY
  ;;
at)
  [ $# -ge 2 ] || { echo "usage: $0 at TIME RUN_DIR..." >&2; exit 2; }
  case $1 in ''|*[!0-9.]*|*.*.*) echo "$0: TIME='$1' must be a non-negative number of tau" >&2; exit 2 ;; esac
  /usr/bin/python3 - "$@" <<PY
import sys
$series_py
at, runs = float(sys.argv[1]), sys.argv[2:]
print(f"# every run at its last sample at or before t = {at:g} tau (runs of equal length: Table 1's comparison)")
print("| e | seed | t (tau) | monomers | 2-5 | 6-50 | 51-59 | 60 | largest | shells | clusters of 6+ | lag (tau) | first shell (tau) |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
short = []
for run in runs:
    parameters = Run(run).parameters()
    e, seed = float(parameters["attraction"]), int(parameters["seed"])
    t, m = series(run, "mass_fractions")
    if t[-1] < at - 1e-6:
        short.append(f"{run} (to {t[-1]:.0f} tau)")
        continue
    k = int(np.searchsorted(t, at + 1e-6)) - 1
    _, big = series(run, "largest_cluster")
    _, shells = series(run, "complete_shells")
    try:
        tn, by_size = series(run, "clusters_by_size")
        n6 = f"{by_size[int(np.searchsorted(tn, t[k] + 1e-6)) - 1, 5:].sum():.0f}"
    except KeyError:
        n6 = "-"
    six = m[: k + 1, 2:].sum(axis=1)
    lag = f"{t[np.argmax(six > 0)]:.0f}" if (six > 0).any() else "-"
    first = f"{t[np.argmax(shells[: k + 1, 0] > 0)]:.0f}" if (shells[: k + 1, 0] > 0).any() else "-"
    print(f"| {e:g} | {seed} | {t[k]:.0f} | " + " | ".join(f"{x:.3f}" for x in m[k])
          + f" | {big[k, 0]:.0f} | {shells[k, 0]:.0f} | {n6} | {lag} | {first} |")
for s in short:
    print(f"# not reached: {s}")
sys.exit(3 if short else 0)
PY
  ;;
window)
  [ $# -eq 2 ] || { echo "usage: $0 window RUN_DIR STEPS" >&2; exit 2; }
  run=$1 steps=$2 events=${WINDOW_EVENTS:-25}
  [ -f "$run/checkpoint.h5" ] || { echo "$0: no checkpoint in $run" >&2; exit 2; }
  read -r from t0 dt < <(/usr/bin/python3 -c "import h5py,sys; h=h5py.File(sys.argv[1],'r')['checkpoint']; print(int(h.attrs['step']), round(float(h.attrs['time']), 3), float(h['config'].attrs['dt']))" "$run/checkpoint.h5")
  win="$run/window$from"
  if [ ! -f "$win/summary.json" ]; then
    if [ -f "$win/checkpoint.h5" ]; then  # a window stopped on the way (Ctrl-C, a signal) goes on
      "$exe" run --restart "$win/checkpoint.h5" -o "$win" >/dev/null
    else
      mkdir -p "$win"
      cp "$run/checkpoint.h5" "$win/start.h5"
      "$exe" run --restart "$win/start.h5" --set steps=$((from + steps)) --set events_every="$events" \
        --set checkpoint_every=0 --set progress_interval=0 -o "$win" >/dev/null
    fi
  fi
  echo "# window from step $from ($t0 tau), $steps steps of $dt, censuses every $events; $(run_stamp)"
  /usr/bin/python3 - "$win" "$events" "$dt" "$steps" <<PY
import json, sys
$series_py
win, events, dt, steps = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4])
m = json.load(open(f"{win}/summary.json"))["scene_measures"]
# At the checkpoint's own interval the tallies go on from it: the window's are the difference.
with h5py.File(f"{win}/start.h5", "r") as h:
    state = h["checkpoint/scene_state"]
    if "events_interval" in state and int(state["events_interval"][0]) == events:
        print("# (the checkpoint tallied at this interval too: its tallies are subtracted)")
        for base in ("growth_events", "loss_events", "clusters_seen", "split_events", "pieces_shed",
                     "merge_events", "assembled_from_monomers"):
            for name in (base, base + "_coarse"):
                if name in state:
                    m[name] = [a - b for a, b in zip(m[name], state[name][:])]
_, f = series(win, "mass_fractions")
print("# mass fractions at the window's first and last sample: " + " ".join(f"{x:.3f}" for x in f[0]) + " -> " + " ".join(f"{x:.3f}" for x in f[-1]))
step_table(m, events, dt)
piece_table(m, events, dt, steps * dt)
PY
  ;;
*)
  echo "usage: $0 run|table|at|window ... (see the script's head)" >&2
  exit 2
  ;;
esac

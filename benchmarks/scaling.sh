#!/usr/bin/env bash
# Strong scaling (fixed N) or weak scaling (fixed N per rank) of a scene, with each step's time
# split into force, neighbour build (of which migration), ghost communication (refresh and the
# rebuild vote), integration and load imbalance (slowest rank's compute less the mean), and the
# messages and bytes each rank sent per step. Every point is run ROUNDS times, rank counts in
# alternating order; the table takes each point's median. A PNG of time per step and efficiency
# goes beside the table when OUT is given.
# usage: benchmarks/scaling.sh strong|weak SCENE RANKS... [-- SCENE_ARGS...]
#   benchmarks/scaling.sh strong lj-fluid 1 2 -- --set n_cells=16
#   benchmarks/scaling.sh weak lj-fluid 1 2 4 8 -- --set n_cells=12   (n_cells for 1 rank; more
#     ranks take n_cells * ranks^(1/3), rounded: N per rank as close as fcc cells allow)
#   ROUNDS (default 3), STEPS (default 2000, after EQUILIBRATION 500 unmeasured), OUT (a folder
#   for the runs' JSON and the plot). Weak scaling scales lj-fluid's n_cells only.
#   TABLE_ONLY=1 runs nothing and tabulates the np<R>_round<K>.json already in OUT (e.g. those
#   benchmarks/gpu_check.sh's scaling part brought back from a lent machine), with CORES the
#   core count of the machine that ran them.
# More ranks than cores are oversubscribed: such points measure the code's overheads, not its
# scaling, and the table says so.
set -euo pipefail
cd "$(dirname "$0")/.."
. benchmarks/common.sh
die() { echo "scaling.sh: error: $*" >&2; exit 2; }
[ $# -ge 3 ] || die "usage: benchmarks/scaling.sh strong|weak SCENE RANKS... [-- SCENE_ARGS...]"
mode=$1 scene=$2
shift 2
[ "$mode" = strong ] || [ "$mode" = weak ] || die "'$mode': give strong or weak"
ranks=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do
  [[ "$1" =~ ^[1-9][0-9]*$ ]] || die "'$1' is not a rank count"
  ranks+=("$1"); shift
done
[ "${1:-}" = "--" ] && shift
args=("$@")
[ ${#ranks[@]} -ge 1 ] || die "give at least one rank count"
if [ "$mode" = weak ]; then
  [ "$scene" = lj-fluid ] || die "weak scaling scales lj-fluid's n_cells; for $scene give N per rank by hand (strong, one rank count at a time)"
fi
rounds=${ROUNDS:-3} steps=${STEPS:-2000} eq=${EQUILIBRATION:-500}
out=${OUT:-$work/scaling}
mkdir -p "$out"
cores=${CORES:-$(nproc)}
base_cells=$(printf '%s\n' "${args[@]}" | sed -n 's/^n_cells=//p' | tail -n 1)
base_cells=${base_cells:-12}
echo "# scaling.sh $mode $scene ${ranks[*]} -- ${args[*]}; rounds $rounds, steps $steps after $eq; $(date -u +%FT%TZ)"
if [ -n "${TABLE_ONLY:-}" ]; then
  echo "# tabulating the runs in $out, made on a machine with $cores cores (its log says which)"
else
  echo "# $cores cores, $(lscpu | sed -n 's/^Model name: *//p' | head -n 1); commit $(git rev-parse --short=12 HEAD)$(git diff --quiet HEAD -- src include problems decomposition || echo ' (modified)')"
fi
for ((round = 1; round <= rounds; ++round)); do
  [ -n "${TABLE_ONLY:-}" ] && break
  order=("${ranks[@]}")
  if [ $((round % 2)) = 0 ]; then  # alternate which rank count runs first
    order=()
    for ((k = ${#ranks[@]} - 1; k >= 0; --k)); do order+=("${ranks[k]}"); done
  fi
  for np in "${order[@]}"; do
    extra=()
    if [ "$mode" = weak ]; then
      cells=$(/usr/bin/python3 -c "print(max(1, round($base_cells * $np ** (1 / 3))))")
      extra=(--set n_cells="$cells")
    fi
    mpirun -q --oversubscribe -np "$np" "$exe" run "$scene" "${args[@]}" "${extra[@]}" \
      --set equilibration_steps="$eq" --set steps="$steps" --set progress_interval=0 \
      --summary-json "$out/np${np}_round$round.json" >/dev/null
  done
done
/usr/bin/python3 - "$out" "$mode" "$cores" "$rounds" "${ranks[@]}" <<'PY'
import json, statistics, sys
out, mode, cores, rounds, ranks = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), [int(r) for r in sys.argv[5:]]
parts = ["force", "neighbour", "migrate", "communicate", "halo_wait", "integrate", "collective_wait",
         "collective_wait_after_build", "imbalance"]
rows = []
for np_ in ranks:
    runs = [json.load(open(f"{out}/np{np_}_round{r}.json")) for r in range(1, rounds + 1)]
    steps = runs[0]["steps"]
    med = lambda f: statistics.median(f(s) for s in runs)
    row = {"ranks": np_, "N": runs[0]["N"], "grid": runs[0]["grid"],
           "step_ms": med(lambda s: s["wall_seconds"] / steps * 1e3),
           "rate": med(lambda s: s["atom_steps_per_second"]),
           "bytes_per_particle": med(lambda s: s["bytes_per_particle"]),
           "msgs": med(lambda s: (s["messages_ghost_refresh"] + s["messages_ghost_build"] + s["messages_migration"]) / steps / s["ranks"]),
           "kbytes": med(lambda s: (s["message_bytes_ghost_refresh"] + s["message_bytes_ghost_build"] + s["message_bytes_migration"]) / steps / s["ranks"] / 1e3)}
    for p in parts:
        # Runs from before a part was timed lack it: nan.
        row[p] = med(lambda s: s.get(f"seconds_{p}", float("nan")) / steps * 1e3)
    rows.append(row)
base = rows[0]
print(f"# median of {rounds} rounds; times in ms per step (slowest rank's, except imbalance: "
      "slowest compute less the mean); neighbour includes migrate; halo_wait (blocked on ghost data) "
      "lies inside communicate, or inside force where the refresh overlaps; collective_wait (in the "
      "step's global reductions: the rebuild vote, the thermostat's sum) inside communicate and "
      "integrate, of it collective_wait_after_build (the thermostat's sum in steps that rebuilt the "
      "list: per step of the run, not per build); messages and kB per rank per step")
print("# ranks  grid    N         step_ms  efficiency  " + "  ".join(f"{p:>11s}" for p in parts)
      + "  msgs  kB/step  B/particle  note")
for r in rows:
    if mode == "strong":
        eff = base["step_ms"] * base["ranks"] / (r["step_ms"] * r["ranks"])
    else:  # weak: time per step at (nearly) fixed N per rank, corrected for the N actually run
        eff = (base["step_ms"] / base["N"] * base["ranks"]) / (r["step_ms"] / r["N"] * r["ranks"])
    note = "oversubscribed: not scaling evidence" if r["ranks"] > cores else ""
    print(f"{r['ranks']:7d}  {r['grid']:6s}  {r['N']:8d}  {r['step_ms']:8.3f}  {eff:10.3f}  "
          + "  ".join(f"{r[p]:11.4f}" for p in parts)
          + f"  {r['msgs']:4.1f}  {r['kbytes']:7.1f}  {r['bytes_per_particle']:10.0f}  {note}")
    r["efficiency"] = eff
# The contention control (benchmarks/gpu_check.sh): as many independent 1-rank runs at once as
# the largest rank count; their median time per step over the 1-rank point's is the machine's
# own slowdown with every core busy, which no decomposition can remove.
import glob
top = rows[-1]["ranks"]
concurrent = [json.load(open(f)) for f in glob.glob(f"{out}/concurrent{top}_round*_k*.json")]
if concurrent and mode == "weak":
    step_ms = statistics.median(c["wall_seconds"] / c["steps"] * 1e3 for c in concurrent)
    slowdown = step_ms / base["step_ms"] * base["N"] / concurrent[0]["N"]
    print(f"# contention control: {len(concurrent)} runs of 1 rank ({concurrent[0]['N']} atoms), "
          f"{top} at once: {step_ms:.3f} ms per step, {slowdown:.3f}x the 1-rank point's; "
          f"{top}-rank efficiency net of it: {rows[-1]['efficiency'] * slowdown:.3f}")
try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (a, b) = plt.subplots(1, 2, figsize=(9, 3.5))
    x = [r["ranks"] for r in rows]
    bottom = [0.0] * len(rows)
    for p in ["force", "neighbour", "communicate", "integrate"]:
        v = [r[p] for r in rows]
        a.bar([str(k) for k in x], v, bottom=bottom, label=p)
        bottom = [u + w for u, w in zip(bottom, v)]
    a.set_xlabel("ranks"); a.set_ylabel("ms per step (slowest rank)"); a.legend(fontsize=8)
    b.plot(x, [r["efficiency"] for r in rows], "o-")
    b.set_xlabel("ranks"); b.set_ylabel(f"{mode} scaling efficiency"); b.set_ylim(0, 1.1)
    fig.tight_layout()
    fig.savefig(f"{out}/scaling_{mode}.png", dpi=110)
    print(f"# plot: {out}/scaling_{mode}.png")
except ImportError:
    print("# no matplotlib: no plot")
PY

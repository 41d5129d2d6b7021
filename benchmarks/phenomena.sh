#!/usr/bin/env bash
# Runs scenes and checks that each shows its emergent phenomenon (scripts/check_phenomenon states
# the criteria): one command, one log per run, a verdict per scene printed last.
#
# usage: benchmarks/phenomena.sh [SCENE...] [--seed S] [--preset P] [--ranks R] [--out DIR]
#                                [--set KEY=VALUE ...] [--checkpoint-every N] [--continue]
#   SCENE: taylor-couette, rayleigh-benard, rotating-drum, vibrated-sawtooth, capsid-assembly
#   (default: all five; capsid-assembly's small preset runs start=shell: the closed side of its
#   hysteresis; its assembly preset grows shells from monomers, ~80 min on one core)
#   --preset: default small (the preset that shows the phenomenon on a 2-core machine)
#   --ranks: MPI ranks per run (default 2); --out: default /tmp/emergent_phenomena
#   --checkpoint-every N: a long run keeps its latest checkpoint (the engine deletes it at the end);
#   --continue: a run that stopped (session end, SIGTERM) goes on from OUT/SCENE/checkpoint.h5,
#   its run.log extended, instead of being refused
#   --seed, --set: passed to the scene (a control run sets what must make the check fail, e.g.
#   --set omega=0 for the drum)
# Each run goes to OUT/SCENE_seedS (OUT/SCENE without --seed): the run's own output, run.log
# (the command, machine, the engine's progress lines) and check.log (the build's commit, what
# the check measured and its verdict).
# Exit: 0 every phenomenon shown, 1 some check failed, 2 a run or the input failed, 3 a run was
# stopped on request with a checkpoint (the engine's exit 5: SIGUSR1 to mpirun or the ranks,
# SIGTERM or SIGINT to the ranks) and nothing failed (2 before 1 before 3). After a SIGTERM to
# mpirun the ranks checkpoint but mpirun exits with its own status (an ERROR line here);
# --continue goes on from that checkpoint all the same.
set -uo pipefail
cd "$(dirname "$0")/.."
scenes=() seed="" preset=small ranks=2 out=/tmp/emergent_phenomena sets=() every=() resume=0
known="taylor-couette rayleigh-benard rotating-drum vibrated-sawtooth capsid-assembly"
while [ $# -gt 0 ]; do
  case $1 in
    --seed) seed=${2:?--seed needs a value}; shift 2 ;;
    --preset) preset=${2:?--preset needs a value}; shift 2 ;;
    --ranks) ranks=${2:?--ranks needs a value}; shift 2 ;;
    --out) out=${2:?--out needs a value}; shift 2 ;;
    --checkpoint-every) every=(--checkpoint-every "${2:?--checkpoint-every needs a value}"); shift 2 ;;
    --continue) resume=1; shift ;;
    --set) sets+=(--set "${2:?--set needs KEY=VALUE}"); shift 2 ;;
    -*) echo "phenomena.sh: unknown option $1" >&2; exit 2 ;;
    *) case " $known " in
         *" $1 "*) scenes+=("$1"); shift ;;
         *) echo "phenomena.sh: no phenomenon criterion for scene '$1' (known: $known)" >&2; exit 2 ;;
       esac ;;
  esac
done
[ ${#scenes[@]} -eq 0 ] && read -r -a scenes <<<"$known"
case $ranks in ''|*[!0-9]*|0) echo "phenomena.sh: --ranks must be a positive integer" >&2; exit 2 ;; esac
exe=${EMERGENT_EXE:-$PWD/build/bin/emergent}
[ -x "$exe" ] || { echo "phenomena.sh: $exe not built (bash scripts/build)" >&2; exit 2; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mkdir -p "$out" || exit 2

status=0
verdicts=()
for scene in "${scenes[@]}"; do
  dir=$out/$scene${seed:+_seed$seed}
  # An earlier run there (and its logs) stays: the engine would refuse it anyway. With --continue
  # a run that left a checkpoint and no summary goes on from it.
  args=()
  if [ $resume -eq 1 ] && [ -e "$dir/checkpoint.h5" ] && [ ! -e "$dir/summary.json" ]; then
    args=(run --restart "$dir/checkpoint.h5" -o "$dir")
    echo "# continued: mpirun -np $ranks emergent ${args[*]}; $(date -u +%FT%TZ)" >>"$dir/run.log"
  elif compgen -G "$dir/trajectory*.h5" >/dev/null || [ -e "$dir/summary.json" ]; then
    verdicts+=("ERROR: $scene: $dir holds an earlier run; choose another --out (or --continue a stopped one)")
    status=2
    continue
  else
    mkdir -p "$dir" || exit 2
    # The capsid check judges a closed shell at small (the preset starts from the open cluster).
    scene_sets=()
    [ "$scene" = capsid-assembly ] && [ "$preset" = small ] && scene_sets=(--set start=shell)
    args=(run "$scene" --preset "$preset" "${scene_sets[@]}" ${seed:+--set seed=$seed} "${sets[@]}"
          "${every[@]}" -o "$dir")
    {
      echo "# command: mpirun -np $ranks emergent ${args[*]}"
      echo "# machine: $(nproc) cores, $(lscpu | sed -n 's/^Model name: *//p' | head -n 1); $(date -u +%FT%TZ)"
    } >"$dir/run.log"
  fi
  start=$(date +%s)
  mpirun -q --oversubscribe -np "$ranks" "$exe" "${args[@]}" >>"$dir/run.log" 2>&1
  rc=$?
  echo "# exit $rc after $(( $(date +%s) - start )) s" >>"$dir/run.log"
  if [ $rc -eq 5 ] && [ -e "$dir/checkpoint.h5" ]; then
    # Stopped on request, not failed: the engine left a checkpoint to go on from.
    verdicts+=("STOPPED: $scene: stopped on request with a checkpoint; go on with the same command and --continue ($dir/run.log)")
    [ $status -eq 0 ] && status=3
    continue
  fi
  if [ $rc -ne 0 ]; then
    verdicts+=("ERROR: $scene: the run failed (exit $rc; $dir/run.log)")
    status=2
    continue
  fi
  # A finished run keeps no checkpoint: it was only there to continue a stopped one.
  rm -f "$dir/checkpoint.h5"
  scripts/check_phenomenon "$dir" >"$dir/check.log" 2>&1
  rc=$?
  cat "$dir/check.log"
  verdict=$(tail -n 1 "$dir/check.log")
  case $rc in
    0) ;;
    1) [ $status -ne 2 ] && status=1 ;;
    *) status=2; verdict="ERROR: $scene: $verdict" ;;
  esac
  verdicts+=("$verdict (seed ${seed:-preset}, $dir)")
done
printf '%s\n' "${verdicts[@]}"
exit $status

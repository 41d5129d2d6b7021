#!/usr/bin/env bash
# SIGTERM (what a batch system sends at a time limit or on cancel, and `kill` by default) stops a
# run at one step on every rank: the checkpoint of that step is whole (readable, the step the
# message names, every particle's finite state, no .tmp left), the exit status is 5 (`emergent
# --help`: stopped on request) and stderr is one line naming the checkpoint and the command that
# continues it; that very command then ends where the uninterrupted run ends: thermo.dat digit for
# digit, observables (vibrated-sawtooth's cycle averages of the flux included), particles and
# summary bit for bit (tests/support/same_continuation.py). On 1 rank, and on 2 ranks each
# signalled (as SLURM signals every task; mpirun passes on the status 5). Not tested: SIGTERM to
# mpirun itself: Open MPI 4.1 sends the ranks SIGTERM and SIGKILL one second later
# (odls_base_sigkill_timeout), and on this loaded machine the ranks' message was lost in 1 of 17
# tries (exit status 1, mpirun's own); with that timeout raised to 30 s the ranks were not
# stopped at all and ran to their end (5 of 5). stop_on_signal.sh covers SIGUSR1 and SIGINT.
# usage: stop_on_sigterm.sh EMERGENT MPIRUN
set -euo pipefail
exe=$1
mpirun=$2
here=$(cd "$(dirname "$0")" && pwd)
dir=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$dir"' EXIT
# 60 vibration cycles: the signal lands mid-run, after step eq + 500, with seconds of the run
# left (5000 steps took ~0.5 s on a quiet machine, and the signal, 0-0.35 s late, missed the run
# in 2 of 3 tries there: exit 143).
eq=1000 steps=30000
common=(vibrated-sawtooth --preset tiny --set equilibration_steps=$eq --set steps=$steps
        --set sample_every=50 --set progress_interval=0 --set output.snapshot_seconds=0)
mpi=("$mpirun" -q --allow-run-as-root --oversubscribe -np 2)
launch() {  # NP ARGS...: exec `emergent ARGS` on NP ranks (exec: signals reach emergent or mpirun)
  local np=$1; shift
  if [ "$np" = 1 ]; then exec "$exe" "$@"; else exec "${mpi[@]}" "$exe" "$@"; fi
}
fail() { echo "FAIL ($case): $*"; exit 1; }
for case in "1 rank" "2 ranks, each signalled"; do
  np=${case%% *}
  out=$dir/${case//[ ,]/_}
  if [ ! -d "$dir/straight$np" ]; then
    rc=0; (launch $np run "${common[@]}" -o "$dir/straight$np" >/dev/null 2>&1) || rc=$?
    [ $rc = 0 ] || fail "the uninterrupted run exited with status $rc"
  fi
  # Progress lines tell when the measured phase (the cycle averages) is under way; the signal
  # comes 0-0.3 s after the first line past step eq + 500, at a random step.
  (launch $np run "${common[@]}" --set progress_interval=0.1 -o "$out" >"$out.log" 2>"$out.err") &
  pid=$!
  for _ in $(seq 1200); do
    last=$(sed -n 's|^step \([0-9]*\)/.*|\1|p' "$out.log" | tail -n 1)
    [ "${last:-0}" -lt $((eq + 500)) ] || break
    kill -0 $pid 2>/dev/null || fail "the run ended before it was signalled: $(cat "$out.err")"
    sleep 0.05
  done
  sleep "0.$((RANDOM % 4))"
  if [ "$np" = 1 ]; then kill -TERM $pid; else kill -TERM $(pgrep -P $pid); fi  # the ranks
  rc=0; wait $pid || rc=$?
  [ $rc = 5 ] || fail "exit status $rc after SIGTERM, expected 5: $(cat "$out.err")"
  [ "$(wc -l <"$out.err")" = 1 ] || fail "not one line on stderr: $(cat "$out.err")"
  line=$(cat "$out.err")
  pattern="^emergent: stopped on request \(SIGTERM\) at step ([0-9]+) of $((eq + steps)); checkpoint $out/checkpoint.h5; continue with: (emergent run --restart $out/checkpoint.h5 -o $out)\$"
  [[ $line =~ $pattern ]] || fail "unexpected line: $line"
  at=${BASH_REMATCH[1]} continue_with=${BASH_REMATCH[2]}
  [ "$at" -lt $((eq + steps)) ] || fail "the signal came after the run's end (step $at): lengthen the run"
  [ ! -e "$out/summary.json" ] || fail "a stopped run wrote a summary as if complete"
  [ ! -e "$out/checkpoint.h5.tmp" ] || fail "checkpoint.h5.tmp left behind"
  /usr/bin/python3 - "$out/checkpoint.h5" "$at" <<'PY' || fail "the checkpoint is not whole"
import sys, h5py, numpy as np
c = h5py.File(sys.argv[1], "r")["checkpoint"]
step, n = int(c.attrs["step"]), c["position"].shape[0]
assert step == int(sys.argv[2]), f"checkpoint at step {step}, the message says {sys.argv[2]}"
for name in ("position", "velocity", "force", "image", "species"):
    a = c[name][:]
    assert a.shape[0] == n and np.isfinite(a).all(), f"{name}: {a.shape}, not {n} finite rows"
# The scene's running state: period, start, then (sum, count) of each cycle begun.
assert n == 490 and len(c["scene_state/flux"][:]) > 2, "no particles or no cycle averages"
PY
  # The message's own command (emergent -> this build; on the run's rank count), into the
  # checkpoint's directory.
  read -r -a args <<<"${continue_with#emergent }"
  rc=0; (launch $np "${args[@]}" >/dev/null 2>"$out.err2") || rc=$?
  [ $rc = 0 ] || fail "'$continue_with' exited with status $rc: $(cat "$out.err2")"
  /usr/bin/python3 "$here/../support/same_continuation.py" "$dir/straight$np" "$out" "$at" \
    "SIGTERM at step $at, $case, continued with the command the message gives"
done

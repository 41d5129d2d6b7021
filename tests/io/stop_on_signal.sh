#!/usr/bin/env bash
# A run sent SIGUSR1 at a random moment (as a batch system does before a time limit) stops on
# every rank at one step, writes a checkpoint there, exits with status 5 and one line; continued
# from that checkpoint it ends bit for bit where the uninterrupted run ends. On 1 and 2 ranks
# (mpirun forwards the signal to each rank at its own moment: the ranks must agree on the step).
# usage: stop_on_signal.sh EMERGENT MPIRUN
set -euo pipefail
exe=$1
mpirun=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
steps=60000  # a few seconds here: long enough for the signal to land mid-run
common=(lj-fluid --set n_cells=6 --set equilibration_steps=0 --set steps=$steps --set sample_every=500
        --set output.every=0 --set progress_interval=0)
# exec: in the background, the signal goes to emergent (or mpirun), not to a subshell.
launch() { local np=$1; shift; if [ "$np" = 1 ]; then exec "$exe" "$@"; else exec "$mpirun" -q --allow-run-as-root --oversubscribe -np "$np" "$exe" "$@"; fi; }
for np in 1 2; do
  (launch $np run "${common[@]}" -o "$dir/straight$np" >/dev/null)
  (launch $np run "${common[@]}" -o "$dir/stopped$np" >/dev/null 2>"$dir/err$np") &
  pid=$!
  # The run has started once its trajectory exists; the signal comes 0.2-1.1 s later.
  for _ in $(seq 200); do [ -f "$dir/stopped$np/trajectory.h5" ] && break; sleep 0.05; done
  sleep "0.$((RANDOM % 10 + 2))"
  kill -USR1 $pid
  rc=0; wait $pid || rc=$?
  [ $rc = 5 ] || { echo "FAIL ($np ranks): exit status $rc after SIGUSR1, expected 5"; cat "$dir/err$np"; exit 1; }
  [ "$(wc -l <"$dir/err$np")" = 1 ] || { echo "FAIL ($np ranks): not one line:"; cat "$dir/err$np"; exit 1; }
  grep -q "^emergent: stopped on request (SIGUSR1) at step [0-9]* of $steps; checkpoint .*checkpoint.h5; continue with: emergent run --restart" "$dir/err$np" \
    || { echo "FAIL ($np ranks): unexpected line: $(cat "$dir/err$np")"; exit 1; }
  [ ! -f "$dir/stopped$np/summary.json" ] || { echo "FAIL ($np ranks): a stopped run wrote a summary as if complete"; exit 1; }
  at=$(grep -o "at step [0-9]*" "$dir/err$np" | grep -o "[0-9]*")
  (launch $np run --restart "$dir/stopped$np/checkpoint.h5" -o "$dir/stopped$np" >/dev/null)
  /usr/bin/python3 "$(dirname "$0")/../support/same_last_frame.py" "$dir/straight$np/trajectory.h5" \
    "$dir/stopped$np/trajectory.from$at.h5" "the run stopped at step $at on $np rank(s) and continued"
done
# Ctrl-C (SIGINT) on one rank stops the same way; a run started with SIGINT ignored (as a
# non-interactive shell starts a background job) keeps ignoring it. The launcher sets the
# disposition, whatever this script inherited (a CI runner in the background has SIGINT ignored).
with_sigint() {  # with_sigint SIG_DFL|SIG_IGN CMD...: exec CMD with SIGINT so
  exec /usr/bin/python3 -c 'import os, signal, sys
signal.signal(signal.SIGINT, getattr(signal, sys.argv[1]))
os.execv(sys.argv[2], sys.argv[2:])' "$@"
}
(with_sigint SIG_DFL "$exe" run "${common[@]}" -o "$dir/interrupted" >/dev/null 2>"$dir/err_int") &
pid=$!
for _ in $(seq 200); do [ -f "$dir/interrupted/trajectory.h5" ] && break; sleep 0.05; done
sleep 0.3
kill -INT $pid
rc=0; wait $pid || rc=$?
[ $rc = 5 ] || { echo "FAIL: exit status $rc after SIGINT, expected 5"; cat "$dir/err_int"; exit 1; }
grep -q "^emergent: stopped on request (SIGINT) at step [0-9]* of $steps; checkpoint .*checkpoint.h5" "$dir/err_int" \
  || { echo "FAIL: unexpected line after SIGINT: $(cat "$dir/err_int")"; exit 1; }
at=$(grep -o "at step [0-9]*" "$dir/err_int" | grep -o "[0-9]*")
"$exe" run --restart "$dir/interrupted/checkpoint.h5" -o "$dir/interrupted" >/dev/null
/usr/bin/python3 "$(dirname "$0")/../support/same_last_frame.py" "$dir/straight1/trajectory.h5" \
  "$dir/interrupted/trajectory.from$at.h5" "the run stopped by SIGINT at step $at and continued"
(with_sigint SIG_IGN "$exe" run "${common[@]}" -o "$dir/ignoring" >/dev/null 2>"$dir/err_ign") &
pid=$!
for _ in $(seq 200); do [ -f "$dir/ignoring/trajectory.h5" ] && break; sleep 0.05; done
kill -INT $pid
sleep 0.3
kill -0 $pid 2>/dev/null || { echo "FAIL: a run started with SIGINT ignored stopped on SIGINT: $(cat "$dir/err_ign")"; exit 1; }
kill -USR1 $pid
rc=0; wait $pid || rc=$?
[ $rc = 5 ] || { echo "FAIL: exit status $rc after SIGUSR1 (SIGINT ignored), expected 5"; cat "$dir/err_ign"; exit 1; }
grep -q "stopped on request (SIGUSR1)" "$dir/err_ign" || { echo "FAIL: $(cat "$dir/err_ign")"; exit 1; }
echo "ok: SIGINT stops a run like SIGUSR1; ignored from the start, it stays ignored"

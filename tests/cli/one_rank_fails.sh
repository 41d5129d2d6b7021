#!/usr/bin/env bash
# An error met on one rank only (a config file or plugin missing on one node) reaches the user
# as one line with the documented exit code, and nothing hangs (ctest's timeout would fail it).
# usage: one_rank_fails.sh EMERGENT MPIRUN EXPECT_ERROR PLUGIN
set -euo pipefail
exe=$1
mpirun=$2
expect=$3
plugin=$4
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
printf 'n_cells = 4\n' >"$dir/cfg_0.ini"
# Rank 1 has no file of its own; rank 0 goes on into the run and waits there.
"$expect" "^emergent: rank 1: error: cannot read config file '.*cfg_1.ini'$" \
  "$mpirun" -q --allow-run-as-root --oversubscribe -np 2 sh -c \
  "exec \"$exe\" run lj-fluid --preset tiny --set progress_interval=0 --config $dir/cfg_\$OMPI_COMM_WORLD_RANK.ini"
"$expect" "^emergent: rank 1: error: cannot load plugin '.*missing_1.so'" \
  "$mpirun" -q --allow-run-as-root --oversubscribe -np 2 sh -c \
  "if [ \$OMPI_COMM_WORLD_RANK = 1 ]; then p=$dir/missing_1.so; else p=$plugin; fi; exec \"$exe\" --plugin \$p run lj-fluid --preset tiny --set progress_interval=0"
# A fault on one rank in the middle of a run, with the trajectory open on every rank: the
# failing rank does not wait in the file's collective close for ranks that never come.
"$expect" --code 3 "^emergent: rank 1: internal error: demo-gas: fault on rank 1 at step 40$" \
  "$mpirun" -q --allow-run-as-root --oversubscribe -np 2 "$exe" --plugin "$plugin" run demo-gas --preset tiny \
  --set fault_rank=1 --set sample_every=10 --set progress_interval=0 -o "$dir/fault"
# The same error on every rank is one line from rank 0, without a rank prefix or a wait.
start=$(date +%s)
"$expect" "^emergent: error: cannot read config file '/nonexistent.ini'$" \
  "$mpirun" -q --allow-run-as-root --oversubscribe -np 2 "$exe" run lj-fluid --config /nonexistent.ini
[ $(( $(date +%s) - start )) -lt 5 ] || { echo "FAIL: a collective error waited"; exit 1; }
echo "ok: one line whichever ranks fail"

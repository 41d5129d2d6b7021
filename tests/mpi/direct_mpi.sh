#!/usr/bin/env bash
# Messages between ranks straight from the back end's memory (mpi_direct=on), the path a
# CUDA-aware MPI takes, run in CI on the checking back end, whose separate memory is handed to MPI
# as device memory would be: every scene's tiny run on 2 ranks gives thermo rows bit for bit
# those of the host back end; and the WCA fluid's plain step then moves no array (its ghosts
# are no longer staged through host memory: the step ledger).
# usage: direct_mpi.sh EMERGENT MPIRUN
set -euo pipefail
. "$(dirname "$0")/../support/mpi_run.sh"
fails=0
for scene in $("$exe" list | awk '{print $1}'); do
  run 2 "$scene" --preset tiny --set backend=host --set neighbour_list=full --set progress_interval=0 \
    -o "$dir/$scene.host"
  run 2 "$scene" --preset tiny --set backend=checking --set mpi_direct=on --set progress_interval=0 \
    -o "$dir/$scene.direct"
  if cmp -s "$dir/$scene.host/thermo.dat" "$dir/$scene.direct/thermo.dat"; then
    echo "$scene: direct messages on checking, 2 ranks: thermo rows identical to host's"
  else
    echo "FAIL: $scene: direct messages on checking differ from host:"
    diff "$dir/$scene.host/thermo.dat" "$dir/$scene.direct/thermo.dat" | head -4
    fails=$((fails + 1))
  fi
done
for direct in off on; do
  run 2 lj-fluid --preset tiny --set thermostat=none --set backend=checking --set mpi_direct=$direct \
    --set progress_interval=0 -o "$dir/wca.$direct" --summary-json "$dir/wca.$direct.json"
done
arrays() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['step_ledger']['plain_step']['arrays'])" "$1"; }
staged=$(arrays "$dir/wca.off.json") direct=$(arrays "$dir/wca.on.json")
echo "WCA plain step on 2 ranks, arrays moved: staged $staged, direct $direct"
# Staged, the refresh copies its messages to and from host memory (so the check below can fail).
[ "$staged" -gt 0 ] || { echo "FAIL: the staged run moved no array: the ledger does not see staging"; fails=$((fails + 1)); }
[ "$direct" -eq 0 ] || { echo "FAIL: with mpi_direct=on a plain step still moved $direct arrays"; fails=$((fails + 1)); }
[ $fails -eq 0 ] || { echo "direct_mpi.sh: $fails failure(s)"; exit 1; }
echo "direct_mpi.sh: every scene bitwise host's, no array moved"

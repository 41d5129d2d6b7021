#!/usr/bin/env bash
# The progress line of rayleigh-benard carries the latest field frame's Nusselt number and cell
# count, the same values the trajectory records for that frame.
# usage: progress_note.sh EMERGENT
set -euo pipefail
exe=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$exe" run rayleigh-benard --preset tiny --set conduction_flux=0.5 --set progress_interval=1e-9 \
  -o "$dir/run" >"$dir/out"
line=$(grep '^step 400/400' "$dir/out") || { echo "FAIL: no progress line for step 400"; exit 1; }
shown=$(printf '%s\n' "$line" | sed -n 's/.*Nu=\([0-9.]*\) cells=\([0-9]*\).*/\1 \2/p')
[ -n "$shown" ] || { echo "FAIL: no Nu=... cells=... in: $line"; exit 1; }
recorded=$(/usr/bin/python3 -c "
import h5py, sys
with h5py.File(sys.argv[1], 'r') as f:
    o = f['observables']
    print('%.3f %d' % (o['nusselt/value'][-1].ravel()[0], o['cell_count/value'][-1].ravel()[0]))
" "$dir/run/trajectory.h5")
[ "$shown" = "$recorded" ] || { echo "FAIL: progress shows '$shown', the trajectory has '$recorded'"; exit 1; }
echo "ok: progress line shows Nu and cells of the last frame ($shown)"

#!/usr/bin/env bash
# A failing run must not damage what an earlier run wrote into the same output directory.
# usage: keeps_previous_output.sh EMERGENT
set -eu
exe=$1
dir=$(mktemp -d)
"$exe" run lj-fluid --preset tiny --set progress_interval=0 -o "$dir" >/dev/null
before=$(sha256sum "$dir/summary.json" "$dir/thermo.dat")
if "$exe" run lj-fluid --preset tiny --set density=-3 -o "$dir" 2>/dev/null; then
  echo "FAIL: bad run succeeded"; exit 1
fi
after=$(sha256sum "$dir/summary.json" "$dir/thermo.dat")
[ "$before" = "$after" ] || { echo "FAIL: output changed by a failed run"; exit 1; }
ls "$dir" | grep -q '\.tmp$' && { echo "FAIL: temporary file left behind"; exit 1; }
rm -rf "$dir"
echo "ok: earlier output intact"

#!/usr/bin/env bash
# What a continued run may change: structural parameters are refused in one line naming them,
# adjustable ones are taken and echoed; without -o the run writes beside its checkpoint; an end
# before the checkpoint's step is refused; a checkpoint whose box is not the scene's is refused;
# a checkpoint older than a parameter continues with the value it was built with (the capsid's
# site_depth_outer, 0.5 before it was a parameter, 0.25 by default now), and a new value for it
# is refused as structural.
# usage: restart_rules.sh EMERGENT EXPECT_ERROR
set -euo pipefail
exe=$1
expect=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$exe" run lj-fluid --preset tiny --set progress_interval=0 --checkpoint-every 100 -o "$dir/run" >/dev/null
cp "$dir/run/checkpoint.h5" "$dir/saved.h5"
"$expect" "density is structural \(the checkpoint was written with density=0.8\); a continued run cannot set it to 0.7" \
  "$exe" run --restart "$dir/run/checkpoint.h5" --set density=0.7
"$expect" "n_cells is structural" "$exe" run --restart "$dir/run/checkpoint.h5" --set n_cells=5
"$expect" "would end at step 210 \(equilibration_steps \+ steps\), before the checkpoint's step 400" \
  "$exe" run --restart "$dir/run/checkpoint.h5" --set steps=10
# The example in docs/running.md: no -o, output goes beside the checkpoint; the changes are echoed.
out=$("$exe" run --restart "$dir/run/checkpoint.h5" --set steps=400 --set dt=0.004 --set progress_interval=0)
grep -q "^emergent: continuing with changed parameters: dt 0.005 -> 0.004, steps 200 -> 400$" <<<"$out" \
  || { echo "FAIL: changes not echoed: $out"; exit 1; }
[ -f "$dir/run/trajectory.from400.h5" ] || { echo "FAIL: no trajectory.from400.h5 beside the checkpoint"; ls "$dir/run"; exit 1; }
grep -q '"steps": 400' "$dir/run/summary.json" || { echo "FAIL: summary not beside the checkpoint"; exit 1; }
# Same value written another way is no change.
out=$("$exe" run --restart "$dir/saved.h5" --set density=8e-1 --set progress_interval=0 -o "$dir/same")
grep -q "continuing with changed" <<<"$out" && { echo "FAIL: an equal value reported as a change"; exit 1; }
# A box that is not the one the scene builds (a damaged or foreign checkpoint).
/usr/bin/python3 - "$dir/saved.h5" <<'PY'
import sys, h5py
with h5py.File(sys.argv[1], "r+") as f:
    f["checkpoint/box"][4] += 0.5
PY
"$expect" "the scene's box differs from the checkpoint's" "$exe" run --restart "$dir/saved.h5" -o "$dir/other"
# An older checkpoint: a capsid run with the note's outer row, its site_depth_outer attribute
# removed as in checkpoints written before the parameter existed. Continued, it ends as the
# straight run with 0.5 (the default 0.25 would move the sites and every energy after).
capsid=(--preset tiny --set progress_interval=0 --set attraction=0.09 --set site_depth_outer=0.5 --set sample_every=20)
"$exe" run capsid-assembly "${capsid[@]}" --set steps=40 -o "$dir/capsid_straight" >/dev/null
"$exe" run capsid-assembly "${capsid[@]}" --set steps=20 --checkpoint-every 20 -o "$dir/capsid_part" >/dev/null
/usr/bin/python3 - "$dir/capsid_part/checkpoint.h5" <<'PY'
import sys, h5py
with h5py.File(sys.argv[1], "r+") as f:
    del f["checkpoint/config"].attrs["site_depth_outer"]
PY
"$expect" "site_depth_outer is structural \(the checkpoint was written with site_depth_outer=0.5\)" \
  "$exe" run --restart "$dir/capsid_part/checkpoint.h5" --set steps=40 --set site_depth_outer=0.25 -o "$dir/capsid_refused"
"$exe" run --restart "$dir/capsid_part/checkpoint.h5" --set steps=40 -o "$dir/capsid_part" >/dev/null
# Bit for bit, as any continuation on one rank (the bodies' spheres binned where the run's
# last build binned them, the bodies where the run had them); the sites 0.25 deep would move
# the potential energy by 2e-3.
if [ "$(tail -n 1 "$dir/capsid_straight/thermo.dat")" != "$(tail -n 1 "$dir/capsid_part/thermo.dat")" ]; then
  echo "FAIL: an older capsid checkpoint did not continue as the run with its own site_depth_outer"
  tail -n 1 "$dir/capsid_straight/thermo.dat" "$dir/capsid_part/thermo.dat"; exit 1
fi
echo "ok: restart rules"

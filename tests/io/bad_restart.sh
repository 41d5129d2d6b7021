#!/usr/bin/env bash
# --restart with a truncated file or a foreign HDF5 file is one clear error line.
# usage: bad_restart.sh EMERGENT EXPECT_ERROR
set -euo pipefail
exe=$1
expect=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$exe" run lj-fluid --preset tiny --set progress_interval=0 --checkpoint-every 100 -o "$dir" >/dev/null
head -c 3000 "$dir/checkpoint.h5" >"$dir/truncated.h5"
"$expect" "cannot open '.*truncated.h5': missing, truncated or not HDF5" "$exe" run --restart "$dir/truncated.h5"
"$expect" "is not an emergent checkpoint" "$exe" run --restart "$dir/trajectory.h5"
"$expect" "cannot open '/nonexistent.h5'" "$exe" run --restart /nonexistent.h5
"$expect" "is a checkpoint of scene 'lj-fluid', not 'other'" "$exe" run other --restart "$dir/checkpoint.h5"
"$expect" "checkpoint_every needs an output directory" "$exe" run lj-fluid --checkpoint-every 10

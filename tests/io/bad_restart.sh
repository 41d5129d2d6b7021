#!/usr/bin/env bash
# --restart with a truncated file, a foreign HDF5 file or a damaged checkpoint is one clear
# error line.
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
# Values no run writes (each found by hand in a checkpoint edited so; before, species 99, a
# negative diameter, an overflowing image, a negative step or NaN time ran on with exit 0, a
# NaN position stopped the run as a run-time fault, n_global -1 was an internal error): one
# line naming the item, exit status 2.
damage() {  # damage NAME PYTHON-STATEMENT (damage_checkpoint.py)
  /usr/bin/python3 "$(dirname "$0")/damage_checkpoint.py" "$dir/checkpoint.h5" "$dir/$1.h5" "$2"
}
check() {  # check NAME PATTERN PYTHON-STATEMENT
  damage "$1" "$3"
  "$expect" "$2" "$exe" run --restart "$dir/$1.h5" -o "$dir/out_$1"
}
check species "particle 5 has species 99, which the scene does not declare" 'c["species"][5] = 99'
check diameter "particle 5 has diameter -1" 'c["diameter"][5] = -1.0'
check position "particle 5 has a non-finite position" 'c["position"][5, 0] = np.nan'
check velocity "particle 5 has a non-finite velocity" 'c["velocity"][5, 1] = np.inf'
check force "particle 5 has a non-finite force" 'c["force"][5, 2] = np.nan'
check image "particle 5 has an image beyond any run's" 'c["image"][5, 0] = 2**31 - 1'
check step "checkpoint attribute 'step' is -5" 'c.attrs["step"] = -5'
check time "checkpoint attribute 'time' is nan" 'c.attrs["time"] = np.nan'
check n_global "checkpoint attribute 'n_global' is -1" 'c.attrs["n_global"] = -1'
check rows "damaged checkpoint \(dataset 'position' is not [0-9]+ x 3, the rows the checkpoint records\)" \
  'c.attrs["n_global"] = int(c.attrs["n_global"]) + 1'
check missing "damaged checkpoint \(no dataset 'velocity'\)" 'del c["velocity"]'
check ranks "checkpoint attribute 'ranks' is 0" 'c.attrs["ranks"] = 0'
check rebuilds "checkpoint attribute 'rebuilds' is -2" 'c.attrs["rebuilds"] = -2'
check series_rows "series is not rows of [0-9]+" \
  'n = c["series"].size; del c["series"]; c["series"] = np.zeros(n + 1)'
check series_nan "series holds a non-finite value" 'c["series"][0, 1] = np.nan'

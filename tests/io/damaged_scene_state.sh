#!/usr/bin/env bash
# A checkpoint whose fields, series or scene state no run could have written is one line naming
# the item, exit status 2; the same checkpoints undamaged continue. Found by editing tiny runs'
# checkpoints by hand: before, a capsid census with a cluster index out of range crashed, an
# empty scalar of the sawtooth's state was an internal error, and NaN sums, negative sample
# counts and state arrays of the wrong length ran on with exit 0.
# usage: damaged_scene_state.sh EMERGENT EXPECT_ERROR
set -euo pipefail
exe=$1
expect=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
for scene in rayleigh-benard capsid-assembly vibrated-sawtooth taylor-couette planar-couette; do
  "$exe" run "$scene" --preset tiny --set steps=200 --set progress_interval=0 --checkpoint-every 200 \
    -o "$dir/$scene" >/dev/null
  "$exe" run --restart "$dir/$scene/checkpoint.h5" --set steps=220 -o "$dir/$scene.cont" >/dev/null
done
check() {  # check SCENE NAME PATTERN PYTHON-STATEMENT (damage_checkpoint.py)
  /usr/bin/python3 "$(dirname "$0")/damage_checkpoint.py" "$dir/$1/checkpoint.h5" "$dir/$2.h5" "$4"
  "$expect" "$3" "$exe" run --restart "$dir/$2.h5" --set steps=220 -o "$dir/out_$2"
}
check rayleigh-benard field_samples "field 'box' has -4 samples" 'c["fields/box"].attrs["samples"] = -4'
check rayleigh-benard field_nan "field 'box' holds a non-finite value" 'c["fields/box"][3] = np.nan'
check rayleigh-benard field_grid "field 'box': the checkpoint's grid holds 1 cells, this run's [0-9]+" \
  'del c["fields/box"]; c["fields/box"] = np.zeros(6); c["fields/box"].attrs["samples"] = 0'
check rayleigh-benard series "series holds a non-finite value" 'c["series"][0, 3] = np.nan'
check rayleigh-benard tallies "exchange_tallies holds a non-finite value" 'c["exchange_tallies"][0] = np.inf'
check rayleigh-benard state_nan "scene_state 'cell_count_samples' holds a non-finite value" \
  'replace("cell_count_samples", [np.nan])'
check rayleigh-benard last_frame "rayleigh-benard: the checkpoint's scene state 'last_frame' holds 1 values, not 4" \
  'replace("last_frame", [1.0])'
check capsid-assembly census_cluster "capsid-assembly: the checkpoint's census 'previous' is not one of this run's capsomers in clusters" \
  's["previous_cluster"][3] = 1e9'
check capsid-assembly census_body "capsid-assembly: the checkpoint's census 'previous' is not one of this run's capsomers in clusters" \
  's["previous_bodies"][3] = 1e12'
check capsid-assembly tally "capsid-assembly: the checkpoint's growth_events is not 60 counts" 's["growth_events"][3] = -1'
check vibrated-sawtooth scalar "vibrated-sawtooth: the checkpoint's scene state 'last_sample_time' holds 0 values, not 1" \
  'replace("last_sample_time", [])'
check vibrated-sawtooth count "vibrated-sawtooth: the checkpoint's velocity profile has a negative count" \
  's["profile_count_0"][0] = -2'
check taylor-couette bins "taylor-couette: the checkpoint's last_radial_velocity has 1 bins, its noise [0-9]+" \
  'replace("last_radial_velocity", [1.0])'
check planar-couette last_frame "planar-couette: the checkpoint's scene state 'last_frame' holds 1 values, not 3" \
  'replace("last_frame", [1.0])'

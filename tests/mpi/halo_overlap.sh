#!/usr/bin/env bash
# Halo refresh overlapped with the interior pair forces (halo_overlap=on) gives the same bits
# as the blocking refresh in the same particle order (ordered): the interior rows are summed
# first either way, and the boundary rows only after the ghosts have arrived. Without either
# (off) the particles keep the plain cell order: that run completes too. Checked on 2 and 4 ranks for the LJ fluid
# and for two granular scenes (contacts with walls and gravity); the summary must say the
# overlap ran and report a non-empty interior, and its time in global reductions within the
# phases that hold them.
# usage: halo_overlap.sh EMERGENT MPIRUN
set -euo pipefail
. "$(dirname "$0")/../support/mpi_run.sh"
# The summary says whether the overlap ran; with it, some rows must be interior.
check_summary() {
    /usr/bin/python3 - "$1" "$2" <<'PY'
import json, sys
d, want = sys.argv[1], sys.argv[2]
s = json.load(open(f"{d}/summary.json"))
if s["halo_overlap"] != (want == "on"):
    sys.exit(f"FAIL: {d}: summary halo_overlap = {s['halo_overlap']}, asked {want}")
if want == "on" and not 0 < s["interior_fraction"] < 1:
    sys.exit(f"FAIL: {d}: interior_fraction = {s['interior_fraction']}, expected in (0, 1)")
if s["seconds_halo_wait"] < 0:
    sys.exit(f"FAIL: {d}: negative halo wait {s['seconds_halo_wait']}")
# The global reductions' time lies inside communicate and integrate (each the slowest rank's),
# and the rebuild vote runs every step: more than nothing.
wait, inside = s["seconds_collective_wait"], s["seconds_communicate"] + s["seconds_integrate"]
if not 0 < wait <= inside:
    sys.exit(f"FAIL: {d}: collective wait {wait} s, expected in (0, {inside}]")
# Of it, the thermostat's sum in steps that rebuilt the list (the fluid has a thermostat and
# rebuilds; the granular bed has none): a part, and more than nothing where both happen. Each
# is the slowest rank's, possibly another rank, so the part is bounded by the whole's own
# bound, not by it.
after = s["seconds_collective_wait_after_build"]
if not 0 <= after <= inside:
    sys.exit(f"FAIL: {d}: collective wait after builds {after} s, expected in [0, {inside}]")
if d.rstrip("/").split("/")[-1].startswith("fluid") and s["neighbour_rebuilds"] > 1 and not after > 0:
    sys.exit(f"FAIL: {d}: no collective wait after {s['neighbour_rebuilds']} builds")
PY
}

fluid=(lj-fluid --preset tiny --set n_cells=8 --set steps=300 --set progress_interval=0)
bed=(granular-bed --preset tiny --set steps=400 --set progress_interval=0)
layer=(rayleigh-benard --preset tiny --set steps=300 --set progress_interval=0)
for scene in fluid bed layer; do
    declare -n args=$scene
    for np in 2 4; do
        for mode in on ordered off; do
            run "$np" "${args[@]}" --set halo_overlap=$mode -o "$dir/$scene$np$mode"
            check_summary "$dir/$scene$np$mode" $mode
        done
        /usr/bin/python3 "$here/../support/same_last_frame.py" "$dir/$scene${np}ordered/trajectory.h5" \
            "$dir/$scene${np}on/trajectory.h5" "$scene on $np ranks with halo_overlap=on"
    done
    unset -n args
done
# One rank has no halo to overlap: the summary says so.
run 1 "${fluid[@]}" --set halo_overlap=on -o "$dir/fluid1"
check_summary "$dir/fluid1" off
echo "ok: overlapped halo refresh is bitwise the blocking one"

#!/usr/bin/env bash
# A scene run stopped half way (its checkpoint written at the last step) and continued with
# --restart into its own directory is bit for bit the uninterrupted run on the same rank count:
# thermo.dat digit for digit, every observable of trajectory.h5 (the scene's running measures:
# vibrated-sawtooth's cycle averages of the flux with their block errors and its velocity
# profiles, taylor-couette's roll census that compares each field frame with the last), the
# particles, the field frames, and the summary's averages and scene measures
# (tests/support/same_continuation.py). On 1 rank and on 2. No tolerance on 1 rank: any
# difference is state the checkpoint lost. On 2 ranks the particles, thermo.dat and the scene
# measures are still bit for bit; the sums a checkpoint keeps as totals (wall tallies, field
# accumulators) go on as the restored total plus each rank's new partial sum, a regrouping that
# costs round-off (5e-16 relative measured; 1e-12 allowed, see same_continuation.py), and so do
# the measures a scene computes from those field frames.
# usage: restart_exact_scenes.sh EMERGENT MPIRUN SCENE
set -euo pipefail
exe=$1
mpirun=$2
scene=$3
here=$(cd "$(dirname "$0")" && pwd)
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
run() {  # NP ARGS...: `emergent run ARGS` on NP ranks; its last lines and exit 1 if it fails
  local np=$1; shift
  local rc=0
  "$mpirun" -q --allow-run-as-root --oversubscribe -np "$np" "$exe" run "$@" >"$dir/log" 2>&1 || rc=$?
  [ $rc = 0 ] || { echo "FAIL: emergent run $* on $np rank(s) exited with status $rc:"; tail -5 "$dir/log"; exit 1; }
}
# Each case: the steps of the stopped runs' ends, the total of measured steps, the settings of
# both runs, and on 2 ranks the regrouped sums.
case $scene in
  taylor-couette)
    # The split at 650 falls inside a field frame (600, 800] whose roll census compares with the
    # frame before, and inside the inner cylinder's speed ramp (t = 2..4 tau: steps 400..800).
    eq=0 splits=650 total=1200
    regrouped=inner_wall_exchange,outer_wall_exchange,radial_velocity_midgap,radial_velocity_rms,fields
    settings=(--preset tiny --set sample_every=50 --set fields.interval=200 --set output.every=400
              --set spin_up_time=2 --set spin_up_omega=0.1 --set spin_up_ramp=2) ;;
  vibrated-sawtooth)
    # 18 cycles of 500 steps after 1000 of settling: the cycle averages have their 16 blocks
    # (a block error, not NaN); the split at 6250 falls half way through cycle 10. A second
    # split at the end of the settling (steps=0), on 1 rank: the drift removed as the measured
    # phase begins must be removed once, before the continuation.
    eq=1000 splits="6250 1000" total=9000 regrouped=
    settings=(--preset tiny --set sample_every=50) ;;
  granular-bed)
    # Contacts with damping and friction need the saved forces of the last step. The split at
    # 1075 is off the sampling grid: the stopped run samples its last step, a row the
    # continuation must drop (the uninterrupted run has none there).
    eq=500 splits="1050 1075" total=1500 regrouped=
    settings=(--preset tiny --set sample_every=50 --set output.every=500) ;;
  *) echo "FAIL: no case for scene '$scene'"; exit 1 ;;
esac
common=(--set equilibration_steps=$eq --set progress_interval=0 --set output.snapshot_seconds=0)
for np in 1 2; do
  d=$dir/np$np
  run $np "$scene" "${settings[@]}" "${common[@]}" --set steps=$total -o "$d/straight"
  [ $np = 1 ] || splits=${splits%% *}  # 2 ranks: the first split only
  for split in $splits; do
    # Stopped at the split (measured steps split - eq), its checkpoint written there.
    run $np "$scene" "${settings[@]}" "${common[@]}" --set steps=$((split - eq)) \
      --checkpoint-every $split -o "$d/at$split"
    /usr/bin/python3 -c 'import h5py, sys; f = h5py.File(sys.argv[1], "r")
s = int(f["checkpoint"].attrs["step"])
sys.exit(0 if s == int(sys.argv[2]) else f"FAIL: checkpoint at step {s}, not {sys.argv[2]}")' \
      "$d/at$split/checkpoint.h5" $split
    run $np --restart "$d/at$split/checkpoint.h5" --set steps=$total --set checkpoint_every=0 \
      -o "$d/at$split"
    /usr/bin/python3 "$here/../support/same_continuation.py" "$d/straight" "$d/at$split" $split \
      "$scene on $np rank(s), stopped at step $split and continued" \
      "$([ $np = 1 ] || echo "$regrouped")"
  done
done

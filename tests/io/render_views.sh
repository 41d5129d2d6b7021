#!/usr/bin/env bash
# scripts/render draws what the run holds: every view of every scene, each image checked by
# tests/support/render_check.py against trajectory.h5 / fields.h5 through the camera matrix the
# view saves: at the projection of every shown point (particle, cell centre) that nothing nearer
# covers, the pixel has the colour computed here for it (species, radial velocity, vorticity,
# cluster size; translucent solvent layer by layer), and at a stream line's points the colour
# of a line that may be in front there (temperature); hidden points are not drawn; far from everything the background is white. --movie makes an MP4 of
# every recorded frame. Bad input (not a run, a view of another scene, a movie of fewer than 10
# frames, a bad size, fields missing) is one line with status 2. Needs ParaView and xvfb
# (scripts/setup --tests): missing, the test fails; EMERGENT_TEST_PARAVIEW=0 skips it (exit 77).
# usage: render_views.sh EMERGENT
set -euo pipefail
exe=$1
root=$(cd "$(dirname "$0")/../.." && pwd)
[ "${EMERGENT_TEST_PARAVIEW:-1}" = 0 ] && { echo "skipped: EMERGENT_TEST_PARAVIEW=0"; exit 77; }
for tool in pvbatch Xvfb ffmpeg ffprobe; do
  command -v $tool >/dev/null || { echo "FAIL: $tool not installed (bash scripts/setup --tests)"; exit 1; }
done
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
check=$root/tests/support/render_check.py
run() { "$exe" run "$@" --set progress_interval=0 >/dev/null; }
render_and_check() {  # RUN VIEW SIZE; pvbatch's own lines on failure
  "$root/scripts/render" "$dir/$1" --view "$2" --size "$3" >/dev/null ||
    { grep -v '^ *[0-9]* *0x' "$dir/$1/render/$2.log" | tail -n 20; exit 1; }
  /usr/bin/python3 "$check" "$dir/$1" "$dir/$1/render/$2.png" "$2"
}
# A drum long enough for a cut-away worth checking (two species).
run rotating-drum --preset tiny --set bodies=200 --set length=40 --set output.every=100 -o "$dir/drum"
for v in particles cutaway section big_grains small_grains; do render_and_check drum $v 500x500; done
run vibrated-sawtooth --preset tiny -o "$dir/sawtooth"
for v in cutaway big_grains; do render_and_check sawtooth $v 500x400; done
run taylor-couette --preset tiny -o "$dir/tc"
render_and_check tc quadrant 500x500
render_and_check tc rolls 300x500
run rayleigh-benard --preset tiny --set fields.grid=6x6x5 -o "$dir/rb"
for v in convection_above convection_oblique convection_below; do render_and_check rb $v 400x400; done
# The check can fail: the same pictures with red and blue swapped are refused.
while read -r r v; do
  pic=$dir/$r/render/$v
  /usr/bin/python3 -c "import sys, matplotlib.image as m; m.imsave(sys.argv[2], m.imread(sys.argv[1])[:, :, 2::-1].copy())" \
    "$pic.png" "$pic.swapped.png"
  cp "$pic.camera.json" "$pic.swapped.camera.json"
  [ ! -f "$pic.lines.csv" ] || cp "$pic.lines.csv" "$pic.swapped.lines.csv"
  if /usr/bin/python3 "$check" "$dir/$r" "$pic.swapped.png" "$v" >/dev/null 2>&1; then
    echo "FAIL: render_check passed $r's $v picture with red and blue swapped"; exit 1
  fi
done <<<"drum particles
rb convection_oblique"
echo "ok: pictures with red and blue swapped fail the check"
# The capsid views: a closed shell (dark blue throughout) and an open 59-cluster with a monomer
# (light orange; the monomer hidden), at e = 0.09 after 200 steps; the early state with its
# translucent solvent.
for start in shell open_shell; do
  run capsid-assembly --preset tiny --set start=$start --set attraction=0.09 --set steps=200 \
    --set output.every=100 -o "$dir/$start"
  render_and_check $start capsid 500x500
done
render_and_check shell capsid_early 500x500
# A shell that drifted across the box's faces (the run's positions moved by half the box) is
# drawn whole: the view shifts the periodic box to put the largest cluster at its centre.
run capsid-assembly --preset tiny --set start=shell --set attraction=0.09 --set steps=200 \
  --set output.every=100 -o "$dir/wrapped"
/usr/bin/python3 - "$dir/wrapped/trajectory.h5" <<'PY'
import sys
import h5py
import numpy as np
with h5py.File(sys.argv[1], "a") as f:
    g = f["particles/bodies"]
    lo, length = g["box/offset"][:], np.diag(g["box/edges/value"][-1])
    g["position/value"][...] = lo + np.mod(g["position/value"][...] + length / 2 - lo, length)
PY
render_and_check wrapped capsid 500x500
# A movie over every recorded frame (0, 100, ..., 1000: 11).
"$root/scripts/render" "$dir/drum" --movie --size 300x300 >/dev/null
n=$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames -of csv=p=0 "$dir/drum/render/particles.mp4")
[ "$n" = 11 ] || { echo "FAIL: the movie has $n frames, the run 11"; exit 1; }
echo "ok: a movie of 11 frames"
# A continued run: the convection movie runs through both segments (6 + 6 field frames), every
# frame with its temperature legend in the strip (once lost after the first frame); its short
# field intervals leave some cells empty (no temperature), as a dilute layer can.
run rayleigh-benard --preset tiny --set fields.grid=6x6x5 --set fields.interval=50 --set steps=300 \
  --checkpoint-every 300 -o "$dir/rb_cont"
run --restart "$dir/rb_cont/checkpoint.h5" --set steps=600 --set checkpoint_every=0 -o "$dir/rb_cont"
"$root/scripts/render" "$dir/rb_cont" --view convection_oblique --movie --size 400x300 >/dev/null
n=$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames -of csv=p=0 "$dir/rb_cont/render/convection_oblique.mp4")
[ "$n" = 12 ] || { echo "FAIL: the continued run's movie has $n frames, its segments 12"; exit 1; }
/usr/bin/python3 - "$dir/rb_cont/render" <<'PY' || exit 1
import glob, json, sys
import matplotlib.image as mpimg
import numpy as np
frames = sorted(glob.glob(sys.argv[1] + "/convection_oblique_0*.png"))
for name in frames:
    img = mpimg.imread(name)[:, :, :3]
    x0 = json.load(open(name[:-4] + ".camera.json"))["strip"][0]  # the strip's left pixel column
    legend = img[:, x0:]
    # The legend's colour bar: saturated pixels (text, the scale bar and the background are grey).
    if np.sum(legend.max(axis=2) - legend.min(axis=2) > 0.4) < 50:
        sys.exit(f"FAIL: no temperature legend in {name}")
print(f"ok: {len(frames)} frames through both segments, each with its legend")
PY
# scripts/replay: the state file of each scene's default view opens the run in ParaView
# (tests/support/state_check.py, under pvbatch: times, points, what is shown).
. "$root/scripts/render_views/headless.sh"
state_check() {  # RUN VIEW; on a private X server, one more try as in scripts/render
  local state
  state=$("$root/scripts/replay" "$dir/$1" --state-only) ||
    { grep -v '^ *[0-9]* *0x' "$dir/$1/render/$2.log" | tail -n 30; exit 1; }
  [ "$state" = "$(cd "$dir/$1" && pwd)/render/$2.pvsm" ] || { echo "FAIL: replay wrote '$state'"; exit 1; }
  local log=$dir/$1/render/$2.check.log
  { headless 400 400 "$log" pvbatch "$root/tests/support/state_check.py" "$state" "$dir/$1" "$2" &&
      tail -n 1 "$log" | grep -q '^ok'; } ||
    { sleep 2; : >"$log"; headless 400 400 "$log" pvbatch "$root/tests/support/state_check.py" "$state" "$dir/$1" "$2" &&
      tail -n 1 "$log" | grep -q '^ok'; } ||
    { echo "FAIL: the state of $1 ($2) does not open the run: $(tail -n 5 "$log")"; exit 1; }
  tail -n 1 "$log"
}
state_check drum cutaway
state_check rb convection_oblique
state_check tc quadrant
state_check shell capsid
rc=0
err=$(env -u DISPLAY "$root/scripts/replay" "$dir/drum" 2>&1 >/dev/null) || rc=$?
[ $rc = 2 ] && [[ "$err" == *"no display"* ]] || { echo "FAIL: replay without a display: status $rc, $err"; exit 1; }
for bad in "$dir/none" "$dir/tc --view rolls" "$dir/tc --view cutaway" "$dir/tc --bogus"; do
  rc=0
  err=$("$root/scripts/replay" $bad --state-only 2>&1 >/dev/null) || rc=$?
  [ $rc = 2 ] && [ "$(wc -l <<<"$err")" = 1 ] || { echo "FAIL: scripts/replay $bad: status $rc, $err"; exit 1; }
done
echo "ok: replay states open their runs; bad input refused in one line"
run rotating-drum --preset tiny -o "$dir/short"
run rayleigh-benard --preset tiny -o "$dir/rb_slab"
for bad in "$dir/none" "$dir/short --movie" "$dir/drum --view capsid" "$dir/drum --view nosuch" \
           "$dir/drum --size 12" "$dir/tc --view cutaway" "$dir/rb_slab --view convection_above" \
           "$dir/short --view rolls"; do
  rc=0
  err=$("$root/scripts/render" $bad 2>&1 >/dev/null) || rc=$?
  [ $rc = 2 ] && [ "$(wc -l <<<"$err")" = 1 ] || { echo "FAIL: scripts/render $bad: status $rc, $err"; exit 1; }
done
echo "ok: bad input refused in one line"

#!/usr/bin/env bash
# scripts/render draws what the run holds (tests/support/render_check.py): the drum's tiny run
# (two species) from above, flat-shaded: at the projection of every particle that no particle
# nearer the camera covers, the pixel has that particle's species colour, and far from all
# particles the background is white; the capsid view of a closed shell and of an open cluster
# the same way, by cluster size, with monomers hidden. --movie makes an MP4 of every recorded frame. Bad input (not a run, an unknown view, a
# movie of fewer than 10 frames, a bad size) is one line with status 2. Needs ParaView and xvfb (scripts/setup --tests):
# missing, the test fails; EMERGENT_TEST_PARAVIEW=0 skips it (exit 77).
# usage: render_particles.sh EMERGENT
set -euo pipefail
exe=$1
root=$(cd "$(dirname "$0")/../.." && pwd)
[ "${EMERGENT_TEST_PARAVIEW:-1}" = 0 ] && { echo "skipped: EMERGENT_TEST_PARAVIEW=0"; exit 77; }
for tool in pvbatch xvfb-run ffmpeg ffprobe; do
  command -v $tool >/dev/null || { echo "FAIL: $tool not installed (bash scripts/setup --tests)"; exit 1; }
done
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$exe" run rotating-drum --preset tiny --set progress_interval=0 --set output.every=100 -o "$dir/drum" >/dev/null
"$root/scripts/render" "$dir/drum" --size 600x600 >/dev/null
check=$root/tests/support/render_check.py
/usr/bin/python3 "$check" "$dir/drum" "$dir/drum/render/particles.png" particles
# The capsid view: a closed shell (dark blue throughout) and an open 59-cluster with a monomer
# (light orange; the monomer hidden), at e = 0.09 after 200 steps.
for start in shell open_shell; do
  "$exe" run capsid-assembly --preset tiny --set start=$start --set attraction=0.09 --set steps=200 \
    --set progress_interval=0 -o "$dir/$start" >/dev/null
  "$root/scripts/render" "$dir/$start" --view capsid --size 500x500 >/dev/null
  /usr/bin/python3 "$check" "$dir/$start" "$dir/$start/render/capsid.png" capsid
done
# A movie over every recorded frame (0, 100, ..., 1000: 11).
"$root/scripts/render" "$dir/drum" --movie --size 300x300 >/dev/null
n=$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames -of csv=p=0 "$dir/drum/render/particles.mp4")
[ "$n" = 11 ] || { echo "FAIL: the movie has $n frames, the run 11"; exit 1; }
echo "ok: a movie of 11 frames"
"$exe" run rotating-drum --preset tiny --set progress_interval=0 -o "$dir/short" >/dev/null
for bad in "$dir/none" "$dir/short --movie" "$dir/drum --view capsid" "$dir/drum --view nosuch" "$dir/drum --size 12"; do
  rc=0
  err=$("$root/scripts/render" $bad 2>&1 >/dev/null) || rc=$?
  [ $rc = 2 ] && [ "$(wc -l <<<"$err")" = 1 ] || { echo "FAIL: scripts/render $bad: status $rc, $err"; exit 1; }
done
echo "ok: bad input refused in one line"

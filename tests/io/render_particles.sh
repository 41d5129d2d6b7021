#!/usr/bin/env bash
# scripts/render draws what the run holds: the drum's tiny run (two species) rendered from above,
# flat-shaded; at the projection of every particle that no particle nearer the camera covers,
# the pixel has that particle's species colour, and far from all particles the background is
# white. --movie makes an MP4 of every recorded frame. Bad input (not a run, an unknown view, a
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
/usr/bin/python3 - "$dir/drum" <<'PY'
import sys
import h5py
import matplotlib.image as mpimg
import numpy as np
run = sys.argv[1]
img = mpimg.imread(f"{run}/render/particles.png")[:, :, :3]
H, W = img.shape[:2]
f = h5py.File(f"{run}/trajectory.h5", "r")
x = f["particles/all/position/value"][-1]
species = f["particles/all/species/value"][-1]
lo = f["particles/all/box/offset"][:]
hi = lo + np.diag(f["particles/all/box/edges/value"][-1])
rgb = np.array([(0.85, 0.15, 0.10), (0.10, 0.35, 0.85)])  # scripts/render_views/particles.py
# The view: orthographic along -z, box centred, its half height (or half width scaled) the
# parallel scale.
c = (lo + hi) / 2
s = max((hi[1] - lo[1]) / 2, (hi[0] - lo[0]) / 2 * H / W)
col = (x[:, 0] - c[0]) / (2 * s * W / H) * W + W / 2
row = (c[1] - x[:, 1]) / (2 * s) * H + H / 2
checked = good = 0
for i in range(len(x)):
    near = np.hypot(col - col[i], row - row[i]) < 8  # points are drawn 6 px wide
    near[i] = False
    if np.any(near & (x[:, 2] > x[i, 2])):
        continue  # something nearer the camera may cover it
    r, k = int(round(row[i])), int(round(col[i]))
    if not (2 <= r < H - 2 and 2 <= k < W - 2):
        continue
    checked += 1
    # The pixel at the centre or one beside it (rounding of the projection) carries the colour.
    patch = img[r - 1:r + 2, k - 1:k + 2].reshape(-1, 3)
    good += np.any(np.all(np.abs(patch - rgb[species[i]]) < 0.02, axis=1))
far = np.ones((H, W), bool)
for i in range(len(x)):
    r, k = int(round(row[i])), int(round(col[i]))
    far[max(0, r - 12):r + 13, max(0, k - 12):k + 13] = False
white = np.all(img[far] > 0.98, axis=1).mean() if far.any() else 0
assert checked >= 50, f"only {checked} uncovered particles to check"
assert good == checked, f"{checked - good} of {checked} uncovered particles lack their species colour"
assert white > 0.999, f"{(1 - white):.2%} of the pixels far from every particle are not background"
print(f"ok: {good} of {checked} uncovered particles in their species colour; background clean")
PY
# A movie over every recorded frame (0, 100, ..., 1000: 11).
"$root/scripts/render" "$dir/drum" --movie --size 300x300 >/dev/null
n=$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames -of csv=p=0 "$dir/drum/render/particles.mp4")
[ "$n" = 11 ] || { echo "FAIL: the movie has $n frames, the run 11"; exit 1; }
echo "ok: a movie of 11 frames"
"$exe" run rotating-drum --preset tiny --set progress_interval=0 -o "$dir/short" >/dev/null
for bad in "$dir/none" "$dir/short --movie" "$dir/drum --view nosuch" "$dir/drum --size 12"; do
  rc=0
  err=$("$root/scripts/render" $bad 2>&1 >/dev/null) || rc=$?
  [ $rc = 2 ] && [ "$(wc -l <<<"$err")" = 1 ] || { echo "FAIL: scripts/render $bad: status $rc, $err"; exit 1; }
done
echo "ok: bad input refused in one line"

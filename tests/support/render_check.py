#!/usr/bin/python3
"""Checks a flat-shaded top view from scripts/render against the run's last frame: at the
projection of every shown point that no nearer shown point covers, the pixel (or one beside it)
has the colour the view gives that point; hidden points that nothing covers stay background;
and far from every point the image is background (white).
usage: render_check.py RUN_DIR PNG particles|capsid"""
import sys

import h5py
import matplotlib.image as mpimg
import numpy as np

run, png, view = sys.argv[1], sys.argv[2], sys.argv[3]
img = mpimg.imread(png)[:, :, :3]
H, W = img.shape[:2]
f = h5py.File(f"{run}/trajectory.h5", "r")
group = f["particles/all" if view == "particles" else "particles/bodies"]
x = group["position/value"][-1]
if view == "particles":  # scripts/render_views/particles.py
    palette = np.array([(0.85, 0.15, 0.10), (0.10, 0.35, 0.85), (0.95, 0.75, 0.10),
                        (0.20, 0.70, 0.25), (0.55, 0.25, 0.70), (0.05, 0.75, 0.75)])
    colour = palette[group["species/value"][-1] % len(palette)]
    shown = np.ones(len(x), bool)
    width = 6
else:  # scripts/render_views/capsid.py
    size = group["cluster_size/value"][-1]
    colour = np.where((size == 60)[:, None], [(0.10, 0.20, 0.60)], [(1.00, 0.75, 0.50)])
    shown = size >= 2
    width = 10
lo = group["box/offset"][:]
hi = lo + np.diag(group["box/edges/value"][-1])
c = (lo + hi) / 2
s = max((hi[1] - lo[1]) / 2, (hi[0] - lo[0]) / 2 * H / W)
col = (x[:, 0] - c[0]) / (2 * s * W / H) * W + W / 2
row = (c[1] - x[:, 1]) / (2 * s) * H + H / 2
checked = good = hidden_checked = hidden_good = 0
for i in range(len(x)):
    near = np.hypot(col - col[i], row - row[i]) < width + 2
    near[i] = False
    r, k = int(round(row[i])), int(round(col[i]))
    if not (2 <= r < H - 2 and 2 <= k < W - 2):
        continue
    patch = img[r - 1:r + 2, k - 1:k + 2].reshape(-1, 3)
    if shown[i]:
        if np.any(near & shown & (x[:, 2] > x[i, 2])):
            continue  # a nearer shown point may cover it
        checked += 1
        good += np.any(np.all(np.abs(patch - colour[i]) < 0.02, axis=1))
    elif not np.any(near & shown):
        hidden_checked += 1
        hidden_good += np.all(patch > 0.98)
far = np.ones((H, W), bool)
for i in np.nonzero(shown)[0]:
    r, k = int(round(row[i])), int(round(col[i]))
    far[max(0, r - 2 * width):r + 2 * width + 1, max(0, k - 2 * width):k + 2 * width + 1] = False
white = np.all(img[far] > 0.98, axis=1).mean() if far.any() else 0
problems = []
if checked < 20:
    problems.append(f"only {checked} uncovered shown points to check")
if good != checked:
    problems.append(f"{checked - good} of {checked} uncovered points lack their colour")
if hidden_good != hidden_checked:
    problems.append(f"{hidden_checked - hidden_good} of {hidden_checked} hidden points were drawn")
if white < 0.999:
    problems.append(f"{1 - white:.2%} of the pixels far from every point are not background")
if problems:
    sys.exit("FAIL (" + view + "): " + "; ".join(problems))
print(f"ok ({view}): {good} of {checked} uncovered points in their colour, {hidden_checked} "
      "hidden points not drawn, background clean")

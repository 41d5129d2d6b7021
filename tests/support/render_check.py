#!/usr/bin/python3
"""Checks an image from scripts/render against the run it shows. The view's camera comes from
the PNG's .camera.json (world -> screen matrix); what each point should look like is computed
here from trajectory.h5 / fields.h5, independently of the view script:
  - at the projection of every shown point that no nearer shown point covers, the pixel (or one
    beside it) has the colour that point maps to;
  - hidden points that nothing covers leave the background;
  - far from every shown point the image is background (white).
usage: render_check.py RUN_DIR PNG VIEW
views: particles capsid capsid_early quadrant cutaway big_grains small_grains rolls
       convection_above convection_oblique convection_below"""
import json
import sys

import h5py
import matplotlib.image as mpimg
import numpy as np

run, png, view = sys.argv[1], sys.argv[2], sys.argv[3]
img = mpimg.imread(png)[:, :, :3]
H, W = img.shape[:2]
cam = json.load(open(png[:-4] + ".camera.json"))
M = np.array(cam["matrix"])
# The views' colours (scripts/render_views/_common.py), restated here.
SPECIES = np.array([(0.85, 0.15, 0.10), (0.10, 0.35, 0.85), (0.95, 0.75, 0.10), (0.20, 0.70, 0.25),
                    (0.55, 0.25, 0.70), (0.05, 0.75, 0.75)])
DIVERGING = [(-1.0, (0.10, 0.25, 0.90)), (0.0, (0.88, 0.88, 0.88)), (1.0, (0.90, 0.10, 0.10))]
THERMAL = [(0.0, (0.10, 0.25, 0.90)), (0.5, (0.95, 0.85, 0.20)), (1.0, (0.90, 0.10, 0.10))]
BIG_RED, SMALL_YELLOW = SPECIES[0], SPECIES[2]


def ramp(stops, lo, hi, value):
    s0, s1 = stops[0][0], stops[-1][0]
    x = np.clip((np.asarray(value, float) - lo) / (hi - lo), 0, 1) * (s1 - s0) + s0
    return np.stack([np.interp(x, [s for s, _ in stops], [c[k] for _, c in stops]) for k in range(3)], -1)


def project(x):
    """Pixel column, row and depth along the view of world points x [n, 3]."""
    h = np.c_[x, np.ones(len(x))] @ M.T
    ndc = h[:, :3] / h[:, 3:4]
    col = (ndc[:, 0] + 1) / 2 * W
    row = (1 - ndc[:, 1]) / 2 * H
    depth = (x - np.array(cam["position"])) @ np.array(cam["direction"])
    return col - 0.5, row - 0.5, depth


def check_points(x, colour, shown, size, hidden=None, tolerance=0.02, only=None):
    """Colour at uncovered shown points, background at uncovered hidden points; returns
    (checked, good, hidden_checked, hidden_good, far-from-points mask); `only`: the points to
    check (default all), every shown point may cover them."""
    col, row, depth = project(x)
    hidden = ~shown if hidden is None else hidden
    checked = good = hidden_checked = hidden_good = 0
    reach = size / 2 + 2  # a square point of `size` pixels covers the centre of another this near
    for i in range(len(x)) if only is None else only:
        r, k = int(round(row[i])), int(round(col[i]))
        if not (2 <= r < H - 2 and 2 <= k < W - 2):
            continue
        near = np.maximum(np.abs(col - col[i]), np.abs(row - row[i])) < reach
        near[i] = False
        patch = img[r - 1:r + 2, k - 1:k + 2].reshape(-1, 3)
        if shown[i]:
            if np.any(near & shown & (depth < depth[i])):
                continue  # a nearer shown point may cover it
            checked += 1
            wanted = np.reshape(colour[i], (-1, 1, 3))  # one colour, or any of several
            good += np.any(np.all(np.abs(patch[None] - wanted) < tolerance, axis=2))
        elif hidden[i] and not np.any(shown & (np.maximum(np.abs(col - col[i]), np.abs(row - row[i])) < reach + 1.5)):
            hidden_checked += 1
            hidden_good += np.all(patch > 0.98)
    far = np.ones((H, W), bool)
    reach = int(size + 2)
    for i in np.nonzero(shown)[0]:
        r, k = int(round(row[i])), int(round(col[i]))
        far[max(0, r - 2 * reach):max(0, r + 2 * reach + 1), max(0, k - 2 * reach):max(0, k + 2 * reach + 1)] = False
    return checked, good, hidden_checked, hidden_good, far


def verdict(checked, good, hidden_checked, hidden_good, far, what, minimum=20):
    problems = []
    white = np.all(img[far] > 0.98, axis=1).mean() if far.any() else 1.0
    if checked < minimum:
        problems.append(f"only {checked} uncovered shown {what} to check")
    if good != checked:
        problems.append(f"{checked - good} of {checked} uncovered {what} lack their colour")
    if hidden_good != hidden_checked:
        problems.append(f"{hidden_checked - hidden_good} of {hidden_checked} hidden points were drawn")
    if white < 0.999:
        problems.append(f"{1 - white:.2%} of the pixels far from every point are not background")
    if problems:
        sys.exit(f"FAIL ({view}): " + "; ".join(problems))
    print(f"ok ({view}): {good} of {checked} uncovered {what} in their colour, {hidden_checked} "
          "hidden points not drawn, background clean")


f = h5py.File(f"{run}/trajectory.h5", "r")
scene = f["parameters"].attrs["scene"].decode()
size = cam.get("point_size", 6)
if view in ("particles", "quadrant", "cutaway", "big_grains", "small_grains", "capsid_early"):
    g = f["particles/all"]
    frames = len(g["position/value"])
    frame = min(1, frames - 1) if view == "capsid_early" else -1
    x = g["position/value"][frame]
    species = g["species/value"][frame]
    shown = np.ones(len(x), bool)
    hidden = None
    tolerance = 0.02
    if view == "particles":
        colour = SPECIES[species % len(SPECIES)]
    elif view == "quadrant":
        v = g["velocity/value"][frame]
        r = np.maximum(np.hypot(x[:, 0], x[:, 1]), 1e-12)
        vr = (x[:, 0] * v[:, 0] + x[:, 1] * v[:, 1]) / r
        a = np.percentile(np.abs(vr), 98)
        colour = ramp(DIVERGING, -a, a, vr)
    elif view in ("cutaway", "big_grains", "small_grains"):
        colour = np.where((species == 1)[:, None], BIG_RED, SMALL_YELLOW)
        if view == "cutaway" and scene == "rotating-drum":  # the near half (x > 0) cut away
            shown = x[:, 0] <= 0
        elif view == "cutaway":  # the sawtooth's front half (y below the middle) cut away
            lo = g["box/offset"][:]
            shown = x[:, 1] >= lo[1] + g["box/edges/value"][-1][1][1] / 2
        else:
            shown = species == (1 if view == "big_grains" else 0)
    else:  # capsid_early: capsomer spheres opaque, solvent translucent grey, sites hidden
        shown = species == 1
        colour = np.tile(SPECIES[1], (len(x), 1))
        solvent = species == 0
        col, row, depth = project(x)
        # Solvent: k translucent grey squares (30 % opaque, grey 0.5) over white give
        # 1 - 0.5 (1 - 0.7^k) whatever their order; checked at pixels no capsomer sphere
        # covers and no square's edge passes near (k is then unambiguous).
        s_half = cam["solvent_point_size"] / 2
        checked = bad = 0
        for i in np.nonzero(solvent)[0][:3000]:
            r, k = int(round(row[i])), int(round(col[i]))
            if not (2 <= r < H - 2 and 2 <= k < W - 2):
                continue
            dc, dr = np.abs(col - k), np.abs(row - r)
            if np.any(shown & (dc < size / 2 + 2) & (dr < size / 2 + 2)):
                continue
            inside = solvent & (np.maximum(dc, dr) < s_half - 1.5)
            edge = solvent & (np.maximum(dc, dr) >= s_half - 1.5) & (np.maximum(dc, dr) <= s_half + 1.5)
            if edge.any() or inside.sum() > 3:
                continue
            checked += 1
            bad += np.any(np.abs(img[r, k] - (1 - 0.5 * (1 - 0.7 ** inside.sum()))) > 0.03)
        if checked < 10 or bad:
            sys.exit(f"FAIL ({view}): {bad} of {checked} solvent pixels not 30 % grey per atom over white")
        print(f"ok ({view}): {checked} solvent pixels translucent grey, layer by layer")
        # Capsomer spheres: their colour where no solvent atom lies in front of them.
        reach = s_half + 2
        over = np.array([shown[i] and np.any(solvent & (np.maximum(np.abs(col - col[i]), np.abs(row - row[i])) < reach)
                                              & (depth < depth[i])) for i in range(len(x))])
        c, gd, hc, hg, far = check_points(x, colour, shown & ~over, size, np.zeros(len(x), bool))
        verdict(c, gd, hc, hg, np.zeros_like(far), "capsomer spheres", minimum=10)
        sys.exit(0)
    verdict(*check_points(x, colour, shown, size, hidden, tolerance), "particles")
elif view == "capsid":
    g = f["particles/bodies"]
    x = g["position/value"][-1]
    csize = g["cluster_size/value"][-1]
    colour = np.where((csize == 60)[:, None], [(0.10, 0.20, 0.60)], [(1.00, 0.75, 0.50)])
    verdict(*check_points(x, colour, csize >= 2, size), "capsomers")
elif view == "rolls":
    # Each cell's centre in its vorticity colour (computed here from fields.h5), where no
    # black stream-function contour passes over it.
    g = h5py.File(f"{run}/fields.h5", "r")["fields/flow"]
    v = g["velocity/value"][-1].mean(axis=1)
    r_edges = np.linspace(g.attrs["r_min"], g.attrs["r_max"], v.shape[1] + 1)
    z_edges = np.linspace(g.attrs["lo"][2], g.attrs["hi"][2], v.shape[0] + 1)
    w = (np.gradient(v[..., 0], z_edges[1] - z_edges[0], axis=0)
         - np.gradient(v[..., 2], r_edges[1] - r_edges[0], axis=1))
    a = np.abs(w).max()
    rc, zc = np.meshgrid((r_edges[1:] + r_edges[:-1]) / 2, (z_edges[1:] + z_edges[:-1]) / 2)
    col, row, _ = project(np.c_[rc.ravel(), zc.ravel(), np.zeros(rc.size)])
    expected = ramp(DIVERGING, -a, a, w.ravel())
    pixels = np.array([img[int(round(r)), int(round(k))] for r, k in zip(row, col)])
    # Under a contour: a black pixel at the centre or next to it (a line passing one pixel away
    # darkens the centre by its anti-aliased edge).
    line = np.array([img[int(round(r)) - 1:int(round(r)) + 2, int(round(k)) - 1:int(round(k)) + 2].sum(axis=2).min()
                     for r, k in zip(row, col)]) < 1.2
    good = np.all(np.abs(pixels - expected) < 0.02, axis=1)
    if line.mean() > 0.4 or not np.all(good | line):
        sys.exit(f"FAIL ({view}): {np.sum(~good & ~line)} of {np.sum(~line)} cells not in their "
                 f"vorticity colour ({line.sum()} under contours)")
    print(f"ok ({view}): {np.sum(~line)} cells in their vorticity colour, {line.sum()} under contours")
elif view.startswith("convection_"):
    # Stream lines: their points (saved by the view) lie in the box with temperatures inside
    # the cells' range; at every point no nearer line passes over, the pixel has the colour of
    # its temperature.
    g = h5py.File(f"{run}/fields.h5", "r")["fields/box"]
    t_cells = g["temperature/value"][-1]
    t_lo, t_hi = t_cells.min(), t_cells.max()
    table = np.genfromtxt(png[:-4] + ".lines.csv", delimiter=",", names=True)
    x = np.c_[table["Points0"], table["Points1"], table["Points2"]]
    t = table["temperature"]
    lo, hi = g.attrs["lo"], g.attrs["hi"]
    if len(x) < 200 or np.any(x < lo - 1e-6) or np.any(x > hi + 1e-6):
        sys.exit(f"FAIL ({view}): {len(x)} stream line points, or some outside the box")
    if np.any(t < t_lo - 1e-6) or np.any(t > t_hi + 1e-6):
        sys.exit(f"FAIL ({view}): stream line temperatures outside the cells' range")
    keep = np.random.default_rng(1).permutation(len(x))[:8000]  # a sample keeps the check quick
    # Colour changes along a line: a pixel beside a point may show a temperature up to half a
    # step away, so any temperature between the neighbouring points' midpoints is accepted.
    t_prev, t_next = np.r_[t[:1], t[:-1]], np.r_[t[1:], t[-1:]]
    span = np.linspace(0, 1, 7)
    t_near = (t[:, None] + np.where(span < 0.5, (t_prev - t)[:, None] * (1 - 2 * span) / 2,
                                    (t_next - t)[:, None] * (2 * span - 1) / 2))
    colour = ramp(THERMAL, t_lo, t_hi, t_near)
    # Lines cover pixels between their points too: consecutive rows of one line (a step of at
    # most 0.1 cell apart) get 4 points in between, which may cover but are not checked.
    step = np.linalg.norm(np.diff(x, axis=0), axis=1)
    joined = np.nonzero(step < 0.2 * np.max((hi - lo) / g.attrs["shape"]) + 1e-9)[0]
    between = np.concatenate([x[joined] + f * (x[joined + 1] - x[joined]) for f in (0.2, 0.4, 0.6, 0.8)])
    x = np.r_[x, between]
    colour = np.r_[colour, np.zeros((len(between), len(span), 3))]
    c, gd, hc, hg, far = check_points(x, colour, np.ones(len(x), bool), cam["line_width"],
                                      np.zeros(len(x), bool), 0.03, only=keep)
    verdict(c, gd, hc, hg, np.zeros_like(far), "stream line points")
else:
    sys.exit(f"render_check.py: no check for view '{view}'")

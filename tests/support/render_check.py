#!/usr/bin/python3
"""Checks an image from scripts/render against the run it shows. The view's camera comes from
the PNG's .camera.json (world -> screen matrix, pixels per unit length, the annotation strip);
what each point should look like is computed here from trajectory.h5 / fields.h5, independently
of the view script:
  - particles are lit spheres: at the projection of every shown sphere that no nearer shown
    sphere covers, the pixel (or one beside it) has the colour that sphere maps to, darkened by
    at most the shading a pixel off the centre gets (or, behind a translucent wall, that colour
    seen through it); where a wall may stand in front (walls drawn solid), at most a fifth of
    them may show the wall's neutral grey instead;
  - an isolated sphere's drawn width is its true diameter;
  - hidden points that nothing covers leave the background;
  - far from every shown point the image is background (white, or a wall's neutral grey where
    the view draws walls), the strip aside;
  - framing: what is drawn spans at least 90 % of the picture left of the strip along one axis
    and leaves its border free;
  - field views: the roll map's flat colours at cell centres; stream lines in the colour of a
    line that may be in front at each of their points.
usage: render_check.py RUN_DIR PNG VIEW
views: particles capsid capsid_early quadrant cutaway section big_grains small_grains rolls
       convection_above convection_oblique convection_below"""
import json
import os
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


def check_points(x, colours, size, only, ends, tolerance=0.02):
    """Lines of `size` pixels drawn through points x: at each point of `only` (not at the image's
    edge) the pixel there, or one beside it, has the colour of a line that may be in front there:
    of the points within a pixel that are not a line's end (their lines surely cover it; a line
    ends at its end point, and the pixels around it blend it with what lies behind) the nearest
    to the camera, or any point nearer still within half the width and 2 pixels (its line may
    reach over it). `ends`: the lines' first and last points.
    `colours(indices)` [m, k, 3]: the colours each of those points may show. Returns (checked, good, sole: checked where one line alone could be
    in front)."""
    col, row, depth = project(x)
    checked = good = sole = 0
    reach = size / 2 + 2
    for i in only:
        r, k = int(round(row[i])), int(round(col[i]))
        if not (2 <= r < H - 2 and 2 <= k < W - 2):
            continue
        apart = np.maximum(np.abs(col - col[i]), np.abs(row - row[i]))
        sure = np.r_[i, np.nonzero((apart < 1) & ~ends)[0]]
        front = sure[np.argmin(depth[sure])]
        candidates = np.r_[front, np.nonzero((apart < reach) & (depth < depth[front]))[0]]
        checked += 1
        sole += len(candidates) == 1
        wanted = np.reshape(colours(candidates), (-1, 1, 3))
        patch = img[r - 1:r + 2, k - 1:k + 2].reshape(-1, 3)
        good += np.any(np.all(np.abs(patch[None] - wanted) < tolerance, axis=2))
    return checked, good, sole


def shared_problems(checked, good, hidden_checked, hidden_good, clean, what, minimum):
    """What every verdict asks: enough points checked, each in its colour (`good` counts those
    that pass), hidden points not drawn, a clean background away from them (`clean`: its share)."""
    problems = []
    if checked < minimum:
        problems.append(f"only {checked} uncovered shown {what} to check")
    if good != checked:
        problems.append(f"{checked - good} of {checked} uncovered {what} lack their colour")
    if hidden_good != hidden_checked:
        problems.append(f"{hidden_checked - hidden_good} of {hidden_checked} hidden points were drawn")
    if clean < 0.999:
        problems.append(f"{1 - clean:.2%} of the pixels far from every point are not background")
    return problems


def line_verdict(checked, good, sole, what, minimum=200):
    """Stream lines: enough points checked, each showing a line that may be in front there
    (`sole`: how many of them could show only their own line, reported)."""
    problems = []
    if checked < minimum:
        problems.append(f"only {checked} {what} to check")
    if good != checked:
        problems.append(f"{checked - good} of {checked} {what} lack the colour of a line in front there")
    if problems:
        sys.exit(f"FAIL ({view}): " + "; ".join(problems))
    print(f"ok ({view}): {good} of {checked} {what} show a line in front there in its colour "
          f"({sole} where one line alone is in front)")


def shade_match(patch, colour, veil=None):
    """Whether a pixel of `patch` [k, 3] is `colour` lit at a tilt of at most ~37 degrees (a
    factor 0.8-1 on every channel: the pixel nearest a projected centre lies within one pixel of
    it, and spheres checked are at least 2.5 pixels in radius), within 0.03 per channel for the
    image's rounding and anti-aliasing; with `veil` also that seen through a translucent flat
    grey wall ((1 - a) lit colour + a grey)."""
    c = np.asarray(colour, float)
    candidates = [(0.0, 0.0)] + ([(veil["opacity"], veil["grey"])] if veil else [])
    for a, grey in candidates:
        under = (patch - a * grey) / (1 - a)
        s = np.clip(under @ c / (c @ c), 0.8, 1.0)
        if np.any(np.all(np.abs(under - s[:, None] * c) < 0.03 / (1 - a), axis=1)):
            return True
    return False


def neutral(pixels, tolerance=0.03):
    """Pixels [k, 3] that are a neutral grey (a wall's)."""
    return np.ptp(pixels, axis=-1) < tolerance


def check_spheres(x, colour, shown, radius, hidden=None, walls=False, veil=None, checked_only=None):
    """Lit spheres: colour (or, walls drawn, at most a fifth neutral grey) at uncovered shown
    centres (of `checked_only` where given: every shown sphere may still cover them),
    background at uncovered hidden centres, true widths of isolated spheres, a clean background
    away from them; returns the verdict's counts."""
    col, row, depth = project(x)
    hidden = ~shown if hidden is None else hidden
    strip = cam["strip"][0]
    checked = good = grey = hidden_checked = hidden_good = widths = widths_good = 0
    on = np.nonzero(shown)[0]
    for i in range(len(x)):
        r, k = int(round(row[i])), int(round(col[i]))
        if not (2 <= r < H - 2 and 2 <= k < strip - 2):
            continue
        dist = np.hypot(col[on] - col[i], row[on] - row[i])
        patch = img[r - 1:r + 2, k - 1:k + 2].reshape(-1, 3)
        if shown[i]:
            if radius[i] < 2.5 or (checked_only is not None and not checked_only[i]):
                continue  # too small to tell its colour from its rim, or not to be checked
            nearer = (depth[on] < depth[i]) & (on != i)
            if np.any(nearer & (dist < radius[on] + 1.5)):
                continue  # a nearer sphere may cover it
            checked += 1
            if shade_match(patch, colour[i], veil):
                good += 1
            elif walls and np.any(neutral(patch)):
                grey += 1
            # An isolated sphere (no other drawn within its diameter and a few pixels): the
            # run of drawn pixels through its centre along the row is its diameter.
            # (Background along the row: white, or a wall's light neutral grey; a sphere's own
            # colour must then not be grey, nor its rim, which darkens towards black.)
            alone = (on != i) & (dist < radius[i] + radius[on] + 3)
            if (not np.any(alone) and radius[i] >= 4 and k - 2 * radius[i] > 0 and k + 2 * radius[i] < strip
                    and np.ptp(colour[i]) > 0.1):
                pixels_along = img[r, :, :]
                line = ~((pixels_along.min(axis=1) >= 0.97)
                         | (walls & neutral(pixels_along) & (pixels_along.mean(axis=1) >= 0.5)))
                left = right = k
                while left > 0 and line[left - 1]:
                    left -= 1
                while right < W - 1 and line[right + 1]:
                    right += 1
                widths += 1
                widths_good += abs((right - left + 1) - 2 * radius[i]) <= 2.5
        elif hidden[i] and not np.any(dist < radius[on] + 3):
            hidden_checked += 1
            hidden_good += np.all(patch > 0.98) or (walls and np.all(neutral(patch)))
    far = np.ones((H, W), bool)
    far[:, strip:] = False
    for i in on:
        r, k, reach = int(round(row[i])), int(round(col[i])), int(np.ceil(radius[i])) + 3
        far[max(0, r - reach):max(0, r + reach + 1), max(0, k - reach):max(0, k + reach + 1)] = False
    return checked, good, grey, hidden_checked, hidden_good, widths, widths_good, far


def sphere_verdict(checked, good, grey, hidden_checked, hidden_good, widths, widths_good, far, what,
                   walls=False, minimum=20):
    pixels = img[far]
    background = np.all(pixels > 0.98, axis=1) | (walls & neutral(pixels))
    clean = background.mean() if len(pixels) else 1.0
    problems = shared_problems(checked, good + grey, hidden_checked, hidden_good, clean, what, minimum)
    if grey > checked / 5:
        problems.append(f"{grey} of {checked} uncovered {what} show a wall's grey instead of their colour")
    if widths_good != widths:
        problems.append(f"{widths - widths_good} of {widths} isolated {what} not drawn at their diameter")
    problems += framing_problems()
    if problems:
        sys.exit(f"FAIL ({view}): " + "; ".join(problems))
    print(f"ok ({view}): {good} of {checked} uncovered {what} in their colour ({grey} behind a wall), "
          f"{widths} isolated at their diameter, {hidden_checked} hidden points not drawn, background "
          "clean, framed")


def framing_problems():
    """The drawn content (anything not white: walls are content too) spans >= 90 % of the
    picture left of the strip along one axis (the view frames it with 3 % to spare on its longer
    side) and stays off its outermost 1 % (nothing cut off)."""
    strip = cam["strip"][0]
    part = img[:, :strip]
    drawn = ~np.all(part > 0.98, axis=2)
    rows, cols = np.nonzero(drawn)
    if len(rows) == 0:
        return ["nothing drawn"]
    span = max((cols.max() - cols.min() + 1) / strip, (rows.max() - rows.min() + 1) / H)
    problems = [] if span >= 0.9 else [f"the content spans {span:.0%} of the picture (framing asks >= 90 %)"]
    edge = max(1, int(0.01 * min(strip, H)))
    border = np.r_[drawn[:edge].ravel(), drawn[-edge:].ravel(), drawn[:, :edge].ravel(), drawn[:, strip - edge:].ravel()]
    if border.mean() > 0.01:
        problems.append(f"{border.mean():.1%} of the picture's border is drawn on: the content is cut off")
    return problems

f = h5py.File(f"{run}/trajectory.h5", "r")
scene = f["parameters"].attrs["scene"].decode()
size = cam.get("point_size", 6)
pixels = cam.get("pixels_per_unit")
if view in ("particles", "quadrant", "cutaway", "section", "big_grains", "small_grains", "capsid_early"):
    g = f["particles/all"]
    frames = len(g["position/value"])
    frame = min(1, frames - 1) if view == "capsid_early" else -1
    x = g["position/value"][frame]
    species = g["species/value"][frame]
    d = g["diameter/value"][frame] if "diameter" in g else np.ones(len(x))
    radius = d / 2 * pixels
    shown = np.ones(len(x), bool)
    hidden = None
    walls = view in ("quadrant", "cutaway", "section", "big_grains", "small_grains")
    if view == "particles":
        colour = SPECIES[species % len(SPECIES)]
    elif view == "quadrant":
        v = g["velocity/value"][frame]
        r = np.maximum(np.hypot(x[:, 0], x[:, 1]), 1e-12)
        vr = (x[:, 0] * v[:, 0] + x[:, 1] * v[:, 1]) / r
        a = np.percentile(np.abs(vr), 98)
        colour = ramp(DIVERGING, -a, a, vr)
    elif view in ("cutaway", "section", "big_grains", "small_grains"):
        colour = np.where((species == 1)[:, None], BIG_RED, SMALL_YELLOW)
        if view == "section":  # grains within 1.5 of the middle cross-section
            z_lo = g["box/offset"][2]
            shown = np.abs(x[:, 2] - (z_lo + g["box/edges/value"][-1][2][2] / 2)) <= 1.5
        elif view == "cutaway" and scene == "rotating-drum":  # the near half (x > 0) cut away
            shown = x[:, 0] <= 0
        elif view == "cutaway":  # the sawtooth's front half (y below the middle) cut away
            lo = g["box/offset"][:]
            shown = x[:, 1] >= lo[1] + g["box/edges/value"][-1][1][1] / 2
        else:
            shown = species == (1 if view == "big_grains" else 0)
    else:  # capsid_early: capsomer spheres opaque, solvent translucent grey, sites hidden
        shown = species == 1
        radius = np.full(len(x), 0.5 * pixels)
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
            if np.any(shown & (np.hypot(dc, dr) < radius + 2)):
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
        counts = check_spheres(x, colour, shown, radius, np.zeros(len(x), bool), checked_only=~over)
        counts = counts[:-1] + (np.zeros_like(counts[-1]),)  # the solvent fills the background
        sphere_verdict(*counts, "capsomer spheres", minimum=10)
        sys.exit(0)
    sphere_verdict(*check_spheres(x, colour, shown, radius, hidden, walls, cam.get("veil")), "particles",
                   walls=walls)
elif view == "capsid":
    g = f["particles/bodies"]
    x = g["position/value"][-1]
    csize = g["cluster_size/value"][-1]
    # The view draws the periodic box shifted so that the largest cluster sits whole at its
    # centre: the same images here, each axis's shift from that cluster's circular mean.
    lo = np.asarray(g["box/offset"][:], float)
    length = np.diag(np.asarray(g["box/edges/value"][-1], float))
    members = x[g["cluster/value"][-1] == g["cluster/value"][-1][np.argmax(csize)]]
    angle = 2 * np.pi * (members - lo) / length
    centre = lo + length * (np.arctan2(np.sin(angle).mean(0), np.cos(angle).mean(0)) % (2 * np.pi)) / (2 * np.pi)
    x = lo + np.mod(x + (lo + length / 2 - centre) - lo, length)
    colour = np.where((csize == 60)[:, None], [(0.10, 0.20, 0.60)], [(1.00, 0.75, 0.50)])
    radius = np.full(len(x), cam["diameter"] / 2 * pixels)
    sphere_verdict(*check_spheres(x, colour, csize >= 2, radius), "capsomers")
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
    # the cells' range; at each point the pixel has the temperature colour of a line that may be
    # in front there.
    # A continued run's last frame is in its last segment's file, which the view draws.
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "../../scripts"))
    from emergentpy import Run
    g = h5py.File(Run(run).fields_paths[-1], "r")["fields/box"]
    t_cells = g["temperature/value"][-1]
    t_lo, t_hi = np.nanmin(t_cells), np.nanmax(t_cells)  # a cell no atom visited has none
    table = np.genfromtxt(png[:-4] + ".lines.csv", delimiter=",", names=True)
    x = np.c_[table["Points0"], table["Points1"], table["Points2"]]
    t = table["temperature"]
    lo, hi = g.attrs["lo"], g.attrs["hi"]
    if len(x) < 200 or np.any(x < lo - 1e-6) or np.any(x > hi + 1e-6):
        sys.exit(f"FAIL ({view}): {len(x)} stream line points, or some outside the box")
    if np.any(t < t_lo - 1e-6) or np.any(t > t_hi + 1e-6):
        sys.exit(f"FAIL ({view}): stream line temperatures outside the cells' range")
    # Lines cover pixels between their points too: consecutive rows of one line (a step of at
    # most 0.1 cell apart) get 4 points in between, which are candidates for what is in front
    # but not checked themselves.
    step = np.linalg.norm(np.diff(x, axis=0), axis=1)
    linked = step < 0.2 * np.max((hi - lo) / g.attrs["shape"]) + 1e-9
    joined = np.nonzero(linked)[0]
    # A line's ends are not checked: the drawn line may stop short of its last point (seen: the
    # 3x3 pixels around it all background), and the pixels at an end blend the line with what
    # lies behind it.
    ends = ~np.r_[linked, False] | ~np.r_[False, linked]
    keep = np.random.default_rng(1).permutation(np.nonzero(~ends)[0])[:8000]  # a sample keeps the check quick
    # Colour changes along a line: a pixel beside a point may show any temperature up to half a
    # step to the neighbouring points of its line (a fifth of a step for the points between).
    t_prev = np.where(np.r_[False, linked], np.r_[t[:1], t[:-1]], t)
    t_next = np.where(np.r_[linked, False], np.r_[t[1:], t[-1:]], t)
    t_a, t_b = np.minimum(t_prev, t_next), np.maximum(t_prev, t_next)
    t_a, t_b = np.minimum(t, (t + t_a) / 2), np.maximum(t, (t + t_b) / 2)
    fractions = (0.2, 0.4, 0.6, 0.8)
    x = np.r_[x, np.concatenate([x[joined] + f * (x[joined + 1] - x[joined]) for f in fractions])]
    t_0, t_1 = np.tile(t[joined], len(fractions)), np.tile(t[joined + 1], len(fractions))
    f = np.repeat(fractions, len(joined))
    t_a = np.r_[t_a, t_0 + (f - 0.1) * (t_1 - t_0)]
    t_b = np.r_[t_b, t_0 + (f + 0.1) * (t_1 - t_0)]

    def colours(indices):
        """Each point's temperature range, sampled finely enough (25 values) that neighbouring
        samples differ by well under the tolerance."""
        s = np.linspace(0, 1, 25)
        return ramp(THERMAL, t_lo, t_hi, t_a[indices, None] + s * (t_b - t_a)[indices, None])

    # The still shows hundreds of thousands of line points, most behind another line within a
    # few pixels: each checked pixel shows the front-most line there, so all are checked.
    ends = np.r_[ends, np.zeros(len(x) - len(ends), bool)]
    checked, good, sole = check_points(x, colours, cam["line_width"], keep, ends, 0.03)
    line_verdict(checked, good, sole, "stream line points")
else:
    sys.exit(f"render_check.py: no check for view '{view}'")

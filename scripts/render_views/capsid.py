"""Run by pvbatch (scripts/render): capsid-assembly's state as the paper shows it, monomers and
solvent hidden: every capsomer in a cluster of two or more, from above (+z looking down),
orthographic, each capsomer a lit sphere whose diameter is the median distance between
neighbouring capsomers in those clusters (so neighbours touch, as their spheres do), complete
shells (clusters of 60) dark blue, incomplete clusters light orange; a still framed on the
clusters, a movie on the box; with the legend, a scale bar and the time. The periodic box is
drawn shifted so that the last frame's largest cluster sits at its centre, whole, not cut by a
face. Reads trajectory.bodies.xmf and its cluster_size and cluster arrays.
usage: pvbatch capsid.py RUN_DIR OUT_PREFIX all|last WIDTH HEIGHT"""
import os
import sys

import h5py
import numpy as np
from paraview.simple import Calculator, Show, Threshold, Xdmf3ReaderT

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _common import box, colour_by_value, corners, framed, render_frames, sphere_view, spheres  # noqa: E402

SHELL_RGB, PARTIAL_RGB = (0.10, 0.20, 0.60), (1.00, 0.75, 0.50)


def capsomer_diameter(x):
    """The median nearest-neighbour distance among the clustered capsomers x (3 where fewer
    than two)."""
    if len(x) < 2:
        return 3.0
    gaps = np.linalg.norm(x[:, None] - x[None], axis=2)
    np.fill_diagonal(gaps, np.inf)
    return float(np.median(gaps.min(axis=1)))


def centring_shift(x, lo, hi):
    """The shift along each axis that moves the periodic centre of the points x (their
    circular mean) to the centre of the box [lo, hi]."""
    length = hi - lo
    angle = 2 * np.pi * (x - lo) / length
    centre = lo + length * np.mod(np.arctan2(np.sin(angle).mean(0), np.cos(angle).mean(0)), 2 * np.pi) / (2 * np.pi)
    return (lo + hi) / 2 - centre


def wrapped(x, shift, lo, hi):
    return lo + np.mod(x + shift - lo, hi - lo)


run, prefix, which, width, height = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), int(sys.argv[5])
lo, hi = box(run, "bodies")
with h5py.File(f"{run}/trajectory.h5", "r") as f:
    x = f["particles/bodies/position/value"][-1]
    size = f["particles/bodies/cluster_size/value"][-1]
    cluster = f["particles/bodies/cluster/value"][-1]
shift = centring_shift(x[cluster == cluster[np.argmax(size)]], lo, hi)
x = wrapped(x, shift, lo, hi)
clustered = x[size >= 2]
diameter = capsomer_diameter(clustered[:2000])
reader = Xdmf3ReaderT(FileName=[f"{run}/trajectory.bodies.xmf"])
moved = Calculator(Input=reader)  # the same shift, wrapped into the box, at every frame
moved.CoordinateResults = 1
moved.Function = " + ".join(
    f"({lo[d]!r} + (coords{axis} + {shift[d] - lo[d]!r}) - {hi[d] - lo[d]!r} * floor((coords{axis} + "
    f"{shift[d] - lo[d]!r}) / {hi[d] - lo[d]!r})) * {unit}"
    for d, (axis, unit) in enumerate((("X", "iHat"), ("Y", "jHat"), ("Z", "kHat"))))
clusters = Threshold(Input=moved)  # monomers (cluster_size 1) hidden
clusters.Scalars = ["POINTS", "cluster_size"]
try:
    clusters.LowerThreshold, clusters.UpperThreshold = 1.5, 1e9
except AttributeError:
    clusters.ThresholdRange = [1.5, 1e9]
complete = Calculator(Input=clusters)  # 1 for a complete shell's capsomers, else 0
complete.ResultArrayName = "complete"
complete.Function = "cluster_size >= 60"
view = sphere_view(width, height)
shown = Show(complete, view)
spheres(shown, diameter)
lut = colour_by_value(shown, "complete", {0: PARTIAL_RGB, 1: SHELL_RGB}, {0: "2-59", 1: "shell (60)"})
# A still is framed on the clusters; a movie on the box, through which they drift (and wrap).
content = clustered if len(clustered) and which != "all" else corners(lo, hi)
camera = framed(view, run, content, width, height, (0, 0, -1), (0, 1, 0), lut, "clusters", pad=diameter / 2)
n = render_frames(view, reader, prefix, which, width, height, extra={**camera, "diameter": diameter})
print(f"{n} image(s) of {run}")

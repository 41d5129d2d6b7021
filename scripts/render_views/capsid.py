"""Run by pvbatch (scripts/render): capsid-assembly's state as the paper shows it, monomers and
solvent hidden: every capsomer in a cluster of two or more, from above (+z looking down),
orthographic and flat-shaded, complete shells (clusters of 60) dark blue, incomplete clusters
light orange. Reads trajectory.bodies.xmf and its cluster_size array.
usage: pvbatch capsid.py RUN_DIR OUT_PREFIX all|last WIDTH HEIGHT"""
import os
import sys

from paraview.simple import Show, Threshold, Xdmf3ReaderT

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _common import box, colour_by_value, flat_points, flat_view, render_frames, top_camera  # noqa: E402

SHELL_RGB, PARTIAL_RGB = (0.10, 0.20, 0.60), (1.00, 0.75, 0.50)

run, prefix, which, width, height = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), int(sys.argv[5])
lo, hi = box(run, "bodies")
reader = Xdmf3ReaderT(FileName=[f"{run}/trajectory.bodies.xmf"])
clusters = Threshold(Input=reader)  # monomers (cluster_size 1) hidden
clusters.Scalars = ["POINTS", "cluster_size"]
try:
    clusters.LowerThreshold, clusters.UpperThreshold = 1.5, 1e9
except AttributeError:
    clusters.ThresholdRange = [1.5, 1e9]
view = flat_view(width, height)
shown = Show(clusters, view)
flat_points(shown, 10)
colour_by_value(shown, "cluster_size", {n: SHELL_RGB if n == 60 else PARTIAL_RGB for n in range(2, 61)})
top_camera(view, lo, hi, width, height)
n = render_frames(view, reader, prefix, which, width, height, extra={"point_size": 10})
print(f"{n} image(s) of {run}")

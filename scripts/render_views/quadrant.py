"""Run by pvbatch (scripts/render): taylor-couette's atoms filling the annulus (a quadrant in the
paper's wedge runs; the walls are not particles), seen obliquely, orthographic and flat-shaded,
coloured by radial velocity v_r = (x v_x + y v_y) / r about the axis (z, through the origin):
blue inward, red outward, light grey at rest, the scale +-a with a the 98th percentile of |v_r|
in the frame shown last. The vortex rolls show as alternating red and blue bands along z.
usage: pvbatch quadrant.py RUN_DIR OUT_PREFIX all|last WIDTH HEIGHT"""
import os
import sys

import h5py
import numpy as np
from paraview.simple import Calculator, Show, Xdmf3ReaderT

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _common import (DIVERGING, box, colour_by_range, flat_points, flat_view, point_size,  # noqa: E402
                     render_frames, set_camera)

DIRECTION = (-1.0, -0.6, -0.7)  # looking down at the quadrant from outside it, above the top end


def radial_velocity_scale(run):
    """a: the 98th percentile of |v_r| at the last frame."""
    with h5py.File(f"{run}/trajectory.h5", "r") as f:
        x = f["particles/all/position/value"][-1]
        v = f["particles/all/velocity/value"][-1]
    r = np.maximum(np.hypot(x[:, 0], x[:, 1]), 1e-12)
    return max(float(np.percentile(np.abs((x[:, 0] * v[:, 0] + x[:, 1] * v[:, 1]) / r), 98)), 1e-12)


run, prefix, which, width, height = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), int(sys.argv[5])
lo, hi = box(run, "all")
a = radial_velocity_scale(run)
reader = Xdmf3ReaderT(FileName=[f"{run}/trajectory.xmf"])
vr = Calculator(Input=reader)
vr.ResultArrayName = "radial_velocity"
vr.Function = "(coordsX*velocity_X+coordsY*velocity_Y)/max(sqrt(coordsX^2+coordsY^2),1e-12)"
view = flat_view(width, height)
shown = Show(vr, view)
size = point_size(lo, hi, width, height, 0.8, DIRECTION)
flat_points(shown, size)
colour_by_range(shown, "POINTS", "radial_velocity", DIVERGING, -a, a)
set_camera(view, lo, hi, width, height, DIRECTION, up=(0, 0, 1))
n = render_frames(view, reader, prefix, which, width, height, extra={"point_size": size, "scale": a})
print(f"{n} image(s) of {run}")

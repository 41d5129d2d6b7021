"""Run by pvbatch (scripts/render): taylor-couette's atoms filling the annulus (a quadrant in the
paper's wedge runs), seen obliquely from outside, orthographic, as spheres at their true
diameters lit from the camera, coloured by radial velocity v_r = (x v_x + y v_y) / r about the
axis (z, through the origin): blue inward, red outward, light grey at rest, the scale +-a with a
the 98th percentile of |v_r| in the frame shown last. The inner cylinder is drawn solid grey,
the outer one as a translucent grey veil in front of the atoms. The vortex rolls show as
alternating red and blue bands along z.
usage: pvbatch quadrant.py RUN_DIR OUT_PREFIX all|last WIDTH HEIGHT"""
import math
import os
import sys

import h5py
import numpy as np
from paraview.simple import Calculator, Show, Xdmf3ReaderT

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _common import (DIVERGING, WALL_GREY, colour_by_range, cylinder_wall, framed, parameter,  # noqa: E402
                     render_frames, ring, sphere_view, spheres)

DIRECTION = (-1.0, -0.6, -0.7)  # looking down at the quadrant from outside it, above the top end
VEIL = 0.12  # the outer cylinder's opacity


def radial_velocity_scale(run):
    """a: the 98th percentile of |v_r| at the last frame."""
    with h5py.File(f"{run}/trajectory.h5", "r") as f:
        x = f["particles/all/position/value"][-1]
        v = f["particles/all/velocity/value"][-1]
    r = np.maximum(np.hypot(x[:, 0], x[:, 1]), 1e-12)
    return max(float(np.percentile(np.abs((x[:, 0] * v[:, 0] + x[:, 1] * v[:, 1]) / r), 98)), 1e-12)


run, prefix, which, width, height = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), int(sys.argv[5])
r_in = parameter(run, "r_inner")
r_out = r_in + parameter(run, "gap")
length = parameter(run, "length")
n_wedge = int(parameter(run, "wedge"))
angle = 2 * math.pi / n_wedge if n_wedge > 1 else None
a = radial_velocity_scale(run)
reader = Xdmf3ReaderT(FileName=[f"{run}/trajectory.xmf"])
vr = Calculator(Input=reader)
vr.ResultArrayName = "radial_velocity"
vr.Function = "(coordsX*velocity_X+coordsY*velocity_Y)/max(sqrt(coordsX^2+coordsY^2),1e-12)"
view = sphere_view(width, height)
inner = cylinder_wall(view, r_in, 0.0, length, opacity=1.0, wedge=angle)
inner.BackfaceRepresentation = "Follow Frontface"
outer = cylinder_wall(view, r_out, 0.0, length, opacity=VEIL, wedge=angle)
outer.BackfaceRepresentation = "Follow Frontface"
shown = Show(vr, view)
spheres(shown)
lut = colour_by_range(shown, "POINTS", "radial_velocity", DIVERGING, -a, a)
# The annulus (or its wedge) is the content: its rims, the atoms reaching half a diameter past.
rims = np.concatenate([ring(r, z, angle=angle or 2 * math.pi) for r in (r_in, r_out) for z in (0.0, length)])
camera = framed(view, run, rims, width, height, DIRECTION, (0, 0, 1), lut, "v_r", pad=0.5)
n = render_frames(view, reader, prefix, which, width, height,
                  extra={**camera, "scale": a, "veil": {"opacity": VEIL, "grey": WALL_GREY}})
print(f"{n} image(s) of {run}")

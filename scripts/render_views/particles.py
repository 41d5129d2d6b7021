"""Run by pvbatch (scripts/render): a run's particles from above (+z looking down), orthographic,
as spheres at their true diameters lit from the camera, each species in its own colour, framed
on the particles, with the species legend, a scale bar and the time; a PNG per frame or for the
last frame.
usage: pvbatch particles.py RUN_DIR OUT_PREFIX all|last WIDTH HEIGHT"""
import os
import sys

import h5py
from paraview.simple import Show, Xdmf3ReaderT

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _common import (SPECIES_RGB, colour_by_value, diameters, framed, render_frames, sphere_view,  # noqa: E402
                     spheres)

run, prefix, which, width, height = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), int(sys.argv[5])
with h5py.File(f"{run}/trajectory.h5", "r") as f:
    g = f["particles/all"]
    x = g["position/value"][-1]
    n_species = int(g["species/value"][:].max()) + 1 if "species" in g else 1
reader = Xdmf3ReaderT(FileName=[f"{run}/trajectory.xmf"])
view = sphere_view(width, height)
shown = Show(reader, view)
spheres(shown)
lut = colour_by_value(shown, "species", {k: SPECIES_RGB[k % len(SPECIES_RGB)] for k in range(n_species)})
camera = framed(view, run, x, width, height, (0, 0, -1), (0, 1, 0), lut, "species", pad=diameters(run).max() / 2)
n = render_frames(view, reader, prefix, which, width, height, extra=camera)
print(f"{n} image(s) of {run}")

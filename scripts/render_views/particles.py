"""Run by pvbatch (scripts/render): a flat-shaded orthographic view of a run's particles from
above (+z looking down), each species in its own colour, written as a PNG per frame or for the
last frame. Flat: no lighting, so a pixel's colour is exactly its particle's species colour.
usage: pvbatch particles.py RUN_DIR OUT_PREFIX all|last WIDTH HEIGHT"""
import os
import sys

import h5py
from paraview.simple import Show, Xdmf3ReaderT

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _common import SPECIES_RGB, box, colour_by_value, flat_points, flat_view, render_frames, top_camera  # noqa: E402

run, prefix, which, width, height = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), int(sys.argv[5])
lo, hi = box(run, "all")
with h5py.File(f"{run}/trajectory.h5", "r") as f:
    n_species = int(f["particles/all/species/value"][:].max()) + 1 if "species" in f["particles/all"] else 1
reader = Xdmf3ReaderT(FileName=[f"{run}/trajectory.xmf"])
view = flat_view(width, height)
shown = Show(reader, view)
flat_points(shown, 6)
colour_by_value(shown, "species", {k: SPECIES_RGB[k % len(SPECIES_RGB)] for k in range(n_species)})
top_camera(view, lo, hi, width, height)
n = render_frames(view, reader, prefix, which, width, height, extra={"point_size": 6})
print(f"{n} image(s) of {run}")

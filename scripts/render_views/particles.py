"""Run by pvbatch (scripts/render): a flat-shaded orthographic view of a run's particles from
above (+z looking down), each species in its own colour, written as a PNG per frame or for the
last frame. Flat: no lighting, so a pixel's colour is exactly its particle's species colour.
usage: pvbatch particles.py RUN_DIR OUT_PREFIX all|last WIDTH HEIGHT"""
import os
import sys

import h5py
from paraview.simple import Show, Xdmf3ReaderT

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _top_view import box, colour_by_value, flat_points, flat_view, render_frames  # noqa: E402

SPECIES_RGB = [(0.85, 0.15, 0.10), (0.10, 0.35, 0.85), (0.95, 0.75, 0.10), (0.20, 0.70, 0.25),
               (0.55, 0.25, 0.70), (0.05, 0.75, 0.75)]

run, prefix, which, width, height = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), int(sys.argv[5])
lo, hi = box(run, "all")
with h5py.File(f"{run}/trajectory.h5", "r") as f:
    n_species = int(f["particles/all/species/value"][:].max()) + 1 if "species" in f["particles/all"] else 1
reader = Xdmf3ReaderT(FileName=[f"{run}/trajectory.xmf"])
view = flat_view(width, height)
shown = Show(reader, view)
flat_points(shown, 6)
colour_by_value(shown, "species", {k: SPECIES_RGB[k % len(SPECIES_RGB)] for k in range(n_species)})
n = render_frames(view, reader, lo, hi, prefix, which, width, height)
print(f"{n} image(s) of {run}")

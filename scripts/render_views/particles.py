"""Run by pvbatch (scripts/render): a flat-shaded orthographic view of a run's particles from
above (+z looking down), each species in its own colour, written as a PNG per frame or for the
last frame. Flat: no lighting, so a pixel's colour is exactly its particle's species colour.
usage: pvbatch particles.py RUN_DIR OUT_PREFIX all|last WIDTH HEIGHT"""
import sys

import h5py
from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetColorTransferFunction, Render,
                             SaveScreenshot, Show, Xdmf3ReaderT, _DisableFirstRenderCameraReset)

SPECIES_RGB = [(0.85, 0.15, 0.10), (0.10, 0.35, 0.85), (0.95, 0.75, 0.10), (0.20, 0.70, 0.25),
               (0.55, 0.25, 0.70), (0.05, 0.75, 0.75)]

run, prefix, which, width, height = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), int(sys.argv[5])
with h5py.File(f"{run}/trajectory.h5", "r") as f:
    lo = f["particles/all/box/offset"][:]
    edges = f["particles/all/box/edges/value"][-1]
    n_species = int(f["particles/all/species/value"][:].max()) + 1 if "species" in f["particles/all"] else 1
hi = [lo[d] + edges[d][d] for d in range(3)]

reader = Xdmf3ReaderT(FileName=[f"{run}/trajectory.xmf"])
view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [width, height]
view.OrientationAxesVisibility = 0
view.Background = [1, 1, 1]
try:
    view.UseColorPaletteForBackground = 0
except AttributeError:
    pass
shown = Show(reader, view)
shown.SetRepresentationType("Points")
shown.PointSize = 6
shown.Ambient, shown.Diffuse, shown.Specular = 1.0, 0.0, 0.0
ColorBy(shown, ("POINTS", "species"))
lut = GetColorTransferFunction("species")
lut.InterpretValuesAsCategories = 1
lut.Annotations = sum(([str(k), str(k)] for k in range(n_species)), [])
lut.IndexedColors = sum((list(SPECIES_RGB[k % len(SPECIES_RGB)]) for k in range(n_species)), [])
# The box fills the image: orthographic, looking down z, x to the right, y up (and the first
# render must not reset the camera to the data's bounds).
_DisableFirstRenderCameraReset()
cx, cy = (lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2
view.CameraParallelProjection = 1
view.CameraPosition = [cx, cy, hi[2] + 10 * (hi[2] - lo[2] + 1)]
view.CameraFocalPoint = [cx, cy, (lo[2] + hi[2]) / 2]
view.CameraViewUp = [0, 1, 0]
view.CameraParallelScale = max((hi[1] - lo[1]) / 2, (hi[0] - lo[0]) / 2 * height / width)
times = list(reader.TimestepValues) or [0.0]
for k, t in enumerate(times if which == "all" else times[-1:]):
    view.ViewTime = t
    Render(view)
    SaveScreenshot(f"{prefix}{k:06d}.png" if which == "all" else f"{prefix}.png", view,
                   ImageResolution=[width, height])
print(f"{len(times) if which == 'all' else 1} image(s) of {run}")

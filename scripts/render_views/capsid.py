"""Run by pvbatch (scripts/render): capsid-assembly's state as the paper shows it, monomers and
solvent hidden: every capsomer in a cluster of two or more, from above (+z looking down),
orthographic and flat-shaded, complete shells (clusters of 60) dark blue, incomplete clusters
light orange. Reads trajectory.bodies.xmf and its cluster_size array.
usage: pvbatch capsid.py RUN_DIR OUT_PREFIX all|last WIDTH HEIGHT"""
import sys

import h5py
from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetColorTransferFunction, Render,
                             SaveScreenshot, Show, Threshold, Xdmf3ReaderT,
                             _DisableFirstRenderCameraReset)

SHELL_RGB, PARTIAL_RGB = (0.10, 0.20, 0.60), (1.00, 0.75, 0.50)

run, prefix, which, width, height = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), int(sys.argv[5])
with h5py.File(f"{run}/trajectory.h5", "r") as f:
    lo = f["particles/bodies/box/offset"][:]
    edges = f["particles/bodies/box/edges/value"][-1]
hi = [lo[d] + edges[d][d] for d in range(3)]

reader = Xdmf3ReaderT(FileName=[f"{run}/trajectory.bodies.xmf"])
clusters = Threshold(Input=reader)  # monomers (cluster_size 1) hidden
clusters.Scalars = ["POINTS", "cluster_size"]
try:
    clusters.LowerThreshold, clusters.UpperThreshold = 1.5, 1e9
except AttributeError:
    clusters.ThresholdRange = [1.5, 1e9]
view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [width, height]
view.OrientationAxesVisibility = 0
view.Background = [1, 1, 1]
try:
    view.UseColorPaletteForBackground = 0
except AttributeError:
    pass
shown = Show(clusters, view)
shown.SetRepresentationType("Points")
shown.PointSize = 10
shown.Ambient, shown.Diffuse, shown.Specular = 1.0, 0.0, 0.0
ColorBy(shown, ("POINTS", "cluster_size"))
lut = GetColorTransferFunction("cluster_size")
lut.InterpretValuesAsCategories = 1
lut.Annotations = sum(([str(n), str(n)] for n in range(2, 61)), [])
lut.IndexedColors = sum((list(SHELL_RGB if n == 60 else PARTIAL_RGB) for n in range(2, 61)), [])
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

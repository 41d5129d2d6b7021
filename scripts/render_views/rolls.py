"""Run by pvbatch (scripts/render): taylor-couette's azimuthally averaged roll map, as the paper's
colour plots: the (r, z) plane of the scene's `flow` field grid (theta-averaged cells), each cell
coloured by the azimuthal vorticity w = dv_r/dz - dv_z/dr of the secondary flow (red one sense of
rotation, blue the other, light grey none; the scale +-max|w| of the frame shown last), with
black contours of the mass stream function psi = integral of rho r v_z dr (the stream lines of
the rolls). r runs to the right, z up, on labelled axes; flat-shaded, orthographic; the strip
holds the vorticity scale, a scale bar and the field frame's time.
usage: pvbatch rolls.py RUN_DIR OUT_PREFIX all|last WIDTH HEIGHT"""
import os
import sys

import h5py
import numpy as np
from paraview.simple import Contour, Hide, Show, Text, TrivialProducer
from vtkmodules.util import numpy_support
from vtkmodules.vtkCommonDataModel import vtkImageData

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _common import (DIVERGING, annotate, colour_by_range, corners, flat, flat_view, frame_content,  # noqa: E402
                     write_camera)
from paraview.simple import Render, SaveScreenshot  # noqa: E402


def roll_frames(run):
    """r and z cell edges, and per frame the vorticity and stream function on the cells."""
    with h5py.File(f"{run}/fields.h5", "r") as f:
        g = f["fields/flow"]
        v = g["velocity/value"][:].mean(axis=2)  # [frames, n_z, n_r, 3]
        rho = g["density/value"][:].mean(axis=2)
        r_edges = np.linspace(g.attrs["r_min"], g.attrs["r_max"], v.shape[2] + 1)
        z_edges = np.linspace(g.attrs["lo"][2], g.attrs["hi"][2], v.shape[1] + 1)
        times = g["velocity/time"][:]
    r = (r_edges[1:] + r_edges[:-1]) / 2
    dr, dz = r_edges[1] - r_edges[0], z_edges[1] - z_edges[0]
    vort = np.gradient(v[..., 0], dz, axis=1) - np.gradient(v[..., 2], dr, axis=2)
    psi = np.cumsum(rho * r[None, None, :] * v[..., 2], axis=2) * dr
    return r_edges, z_edges, vort, psi, times


def image(origin, spacing, dims, name, values, cells):
    img = vtkImageData()
    img.SetOrigin(*origin, 0.0)
    img.SetSpacing(*spacing, 1.0)
    img.SetExtent(0, dims[0] - 1, 0, dims[1] - 1, 0, 0)
    array = numpy_support.numpy_to_vtk(np.ascontiguousarray(values.ravel(), dtype=np.float64), deep=1)
    array.SetName(name)
    (img.GetCellData() if cells else img.GetPointData()).AddArray(array)
    source = TrivialProducer()
    source.GetClientSideObject().SetOutput(img)
    return source


run, prefix, which, width, height = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), int(sys.argv[5])
r_edges, z_edges, vort, psi, times = roll_frames(run)
a = max(float(np.abs(vort[-1]).max()), 1e-12)
dr, dz = r_edges[1] - r_edges[0], z_edges[1] - z_edges[0]
nz, nr = vort.shape[1:]
view = flat_view(width, height)
lo, hi = np.array([r_edges[0], z_edges[0], 0.0]), np.array([r_edges[-1], z_edges[-1], 0.0])
# Room around the map for the axes' ticks and titles (a tenth of its larger side).
framing = frame_content(view, corners(lo, hi), width, height, (0, 0, -1), (0, 1, 0), pad=0.1 * float(np.max(hi - lo)))
view.AxesGrid.Visibility = 1
view.AxesGrid.XTitle, view.AxesGrid.YTitle = "r (sigma)", "z (sigma)"
view.AxesGrid.ShowGrid = 0
for part in ("XTitleColor", "YTitleColor", "XLabelColor", "YLabelColor", "GridColor"):
    setattr(view.AxesGrid, part, [0.0, 0.0, 0.0])
view.AxesGrid.AxesToLabel = 1 | 2  # the edges at min y (r, below) and min x (z, on the left)
view.AxesGrid.UseCustomBounds = 1  # the map's, not the scale bar's
view.AxesGrid.CustomBounds = [r_edges[0], r_edges[-1], z_edges[0], z_edges[-1], 0.0, 0.0]
clock = Show(Text(Text=""), view)
clock.WindowLocation = "Any Location"
clock.Position = [1 - framing["strip"] + 0.02, 0.06]
clock.Color, clock.FontSize = [0.0, 0.0, 0.0], max(8, min(14, int(framing["strip"] * width / 9)))
strip = None
frames = range(len(vort)) if which == "all" else [len(vort) - 1]
shown = []
for k, frame in enumerate(frames):
    for proxy in shown:
        Hide(proxy, view)
    cells = image((r_edges[0], z_edges[0]), (dr, dz), (nr + 1, nz + 1), "vorticity", vort[frame], True)
    map_shown = Show(cells, view)
    map_shown.SetRepresentationType("Surface")
    flat(map_shown)
    lut = colour_by_range(map_shown, "CELLS", "vorticity", DIVERGING, -a, a)
    if strip is None:
        strip = annotate(view, framing, "sigma", lut, "vorticity", time=False)
    clock.Input.Text = f"t = {times[frame]:.1f} tau"
    shown = [cells]
    if nr > 1 and nz > 1 and np.ptp(psi[frame]) > 0:
        centres = image((r_edges[0] + dr / 2, z_edges[0] + dz / 2), (dr, dz), (nr, nz), "psi", psi[frame], False)
        lines = Contour(Input=centres)
        lines.ContourBy = ["POINTS", "psi"]
        lines.Isosurfaces = list(np.linspace(psi[frame].min(), psi[frame].max(), 10)[1:-1])
        lines_shown = Show(lines, view)
        lines_shown.ColorArrayName = ["POINTS", ""]
        lines_shown.AmbientColor = lines_shown.DiffuseColor = [0, 0, 0]
        lines_shown.LineWidth = 2
        flat(lines_shown)
        shown.append(lines)
    Render(view)
    name = f"{prefix}{k:06d}" if which == "all" else prefix
    SaveScreenshot(f"{name}.png", view, ImageResolution=[width, height])
    write_camera(view, f"{name}.camera.json", width, height, {**strip, "scale": a})
print(f"{len(frames)} image(s) of {run}")

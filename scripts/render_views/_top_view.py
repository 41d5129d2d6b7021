"""Shared by the views (scripts/render_views/*.py): the box of a run, a flat-shaded white view,
an orthographic camera looking down z with the box filling the image, and the frame loop."""
import h5py
from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetColorTransferFunction, Render,
                             SaveScreenshot, _DisableFirstRenderCameraReset)


def box(run, group):
    """Lower and upper corners of the box at the last frame of /particles/<group>."""
    with h5py.File(f"{run}/trajectory.h5", "r") as f:
        lo = f[f"particles/{group}/box/offset"][:]
        edges = f[f"particles/{group}/box/edges/value"][-1]
    return lo, [lo[d] + edges[d][d] for d in range(3)]


def flat_view(width, height):
    view = GetActiveViewOrCreate("RenderView")
    view.ViewSize = [width, height]
    view.OrientationAxesVisibility = 0
    view.Background = [1, 1, 1]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    return view


def flat_points(shown, size):
    """Points of `size` pixels without lighting: a pixel's colour is exactly its point's."""
    shown.SetRepresentationType("Points")
    shown.PointSize = size
    shown.Ambient, shown.Diffuse, shown.Specular = 1.0, 0.0, 0.0


def colour_by_value(shown, array, colours):
    """Colours points by the integer values of a point array, value -> (r, g, b), exactly."""
    ColorBy(shown, ("POINTS", array))
    lut = GetColorTransferFunction(array)
    lut.InterpretValuesAsCategories = 1
    lut.Annotations = sum(([str(v), str(v)] for v in colours), [])
    lut.IndexedColors = sum((list(colours[v]) for v in colours), [])


def render_frames(view, reader, lo, hi, prefix, which, width, height):
    """Looks down z at the box (x right, y up; the first render must not reset the camera to the
    data's bounds) and saves the last frame as PREFIX.png or every frame as PREFIXNNNNNN.png."""
    _DisableFirstRenderCameraReset()
    cx, cy = (lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2
    view.CameraParallelProjection = 1
    view.CameraPosition = [cx, cy, hi[2] + 10 * (hi[2] - lo[2] + 1)]
    view.CameraFocalPoint = [cx, cy, (lo[2] + hi[2]) / 2]
    view.CameraViewUp = [0, 1, 0]
    view.CameraParallelScale = max((hi[1] - lo[1]) / 2, (hi[0] - lo[0]) / 2 * height / width)
    times = list(reader.TimestepValues) or [0.0]
    chosen = times if which == "all" else times[-1:]
    for k, t in enumerate(chosen):
        view.ViewTime = t
        Render(view)
        SaveScreenshot(f"{prefix}{k:06d}.png" if which == "all" else f"{prefix}.png", view,
                       ImageResolution=[width, height])
    return len(chosen)

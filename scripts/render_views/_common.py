"""Shared by the views (scripts/render_views/*.py): reading a run, a flat-shaded white view,
colour maps a check can recompute exactly, cameras, and the frame loop. Every saved image gets a
PREFIX.camera.json beside it with the camera's world-to-screen matrix, so a check (and a user)
can find where any point of the run lands in the picture."""
import json
import os

import h5py
import numpy as np
from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetColorTransferFunction,
                             GetOpacityTransferFunction, Render, SaveScreenshot, SaveState,
                             _DisableFirstRenderCameraReset)

# One categorical palette for species and cluster kinds, and the diverging map of signed values
# (blue, light grey, red; interpolated in RGB so a check can recompute a pixel's colour).
SPECIES_RGB = [(0.85, 0.15, 0.10), (0.10, 0.35, 0.85), (0.95, 0.75, 0.10), (0.20, 0.70, 0.25),
               (0.55, 0.25, 0.70), (0.05, 0.75, 0.75)]
DIVERGING = [(-1.0, (0.10, 0.25, 0.90)), (0.0, (0.88, 0.88, 0.88)), (1.0, (0.90, 0.10, 0.10))]
# Temperature, cold to hot (blue, yellow, red).
THERMAL = [(0.0, (0.10, 0.25, 0.90)), (0.5, (0.95, 0.85, 0.20)), (1.0, (0.90, 0.10, 0.10))]


def scene(run):
    with h5py.File(f"{run}/trajectory.h5", "r") as f:
        return f["parameters"].attrs["scene"].decode()


def parameter(run, name):
    with h5py.File(f"{run}/trajectory.h5", "r") as f:
        return float(f["parameters"].attrs[name])


def box(run, group):
    """Lower and upper corners of the box at the last frame of /particles/<group>."""
    with h5py.File(f"{run}/trajectory.h5", "r") as f:
        lo = f[f"particles/{group}/box/offset"][:]
        edges = f[f"particles/{group}/box/edges/value"][-1]
    return np.array(lo, float), np.array([lo[d] + edges[d][d] for d in range(3)], float)


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


def flat(shown):
    """No lighting: a pixel's colour is exactly the colour its data maps to."""
    shown.Ambient, shown.Diffuse, shown.Specular = 1.0, 0.0, 0.0


def flat_points(shown, size):
    """Square points of `size` pixels, unlit."""
    shown.SetRepresentationType("Points")
    shown.PointSize = size
    flat(shown)


def colour_by_value(shown, array, colours):
    """Colours points by the integer values of a point array, value -> (r, g, b), exactly."""
    ColorBy(shown, ("POINTS", array))
    lut = GetColorTransferFunction(array)
    lut.InterpretValuesAsCategories = 1
    lut.Annotations = sum(([str(v), str(v)] for v in colours), [])
    lut.IndexedColors = sum((list(colours[v]) for v in colours), [])


def colour_by_range(shown, association, array, stops, lo, hi):
    """Colours by a scalar through `stops` [(s in [-1,1] or [0,1], rgb)] mapped onto [lo, hi],
    linearly in RGB, not discretised, clamped outside."""
    ColorBy(shown, (association, array))
    lut = GetColorTransferFunction(array)
    lut.InterpretValuesAsCategories = 0
    lut.ColorSpace = "RGB"
    lut.Discretize = 0
    s0, s1 = stops[0][0], stops[-1][0]
    lut.RGBPoints = sum(([lo + (s - s0) / (s1 - s0) * (hi - lo), *rgb] for s, rgb in stops), [])
    lut.AutomaticRescaleRangeMode = "Never"
    GetOpacityTransferFunction(array).RescaleTransferFunction(lo, hi)
    lut.RescaleTransferFunction(lo, hi)
    shown.SetScalarBarVisibility(GetActiveViewOrCreate("RenderView"), False)


def map_colour(stops, lo, hi, value):
    """The colour colour_by_range gives `value` (numpy, for checks and legends)."""
    s0, s1 = stops[0][0], stops[-1][0]
    x = np.clip((np.asarray(value, float) - lo) / (hi - lo), 0, 1) * (s1 - s0) + s0
    return np.stack([np.interp(x, [s for s, _ in stops], [c[k] for _, c in stops]) for k in range(3)], -1)


def point_size(lo, hi, width, height, diameter, direction):
    """Pixels across a sphere of `diameter` in an orthographic view framing the box (see camera)."""
    _, _, scale = framing(lo, hi, width, height, direction)
    return max(2, int(round(diameter * height / (2 * scale))))


def framing(lo, hi, width, height, direction, up=None):
    """Camera up vector, right vector and parallel scale for looking along `direction` at the
    box so that it fills the image."""
    d = np.asarray(direction, float) / np.linalg.norm(direction)
    if up is None:
        up = (0, 1, 0) if abs(d[1]) < 0.9 else (0, 0, 1)
    up = np.asarray(up, float)
    up = up - d * (up @ d)
    up /= np.linalg.norm(up)
    right = np.cross(d, up)
    corners = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])])
    c = (lo + hi) / 2
    half_w = np.abs((corners - c) @ right).max()
    half_h = np.abs((corners - c) @ up).max()
    return up, right, max(half_h, half_w * height / width) * 1.02


def set_camera(view, lo, hi, width, height, direction, up=None):
    """An orthographic camera looking along `direction` at the box's centre, the box in frame
    (the first render must not reset the camera to the data's bounds)."""
    _DisableFirstRenderCameraReset()
    d = np.asarray(direction, float) / np.linalg.norm(direction)
    up, _, scale = framing(lo, hi, width, height, d, up)
    c = (lo + hi) / 2
    view.CameraParallelProjection = 1
    view.CameraFocalPoint = list(c)
    view.CameraPosition = list(c - d * 10 * (np.linalg.norm(hi - lo) + 1))
    view.CameraViewUp = list(up)
    view.CameraParallelScale = scale


def write_camera(view, path, width, height, extra=None):
    """The world -> normalised-device matrix (x, y in [-1, 1], pixel column (x+1)/2*W, row
    (1-y)/2*H), the camera's position and its direction of projection."""
    cam = view.GetActiveCamera()
    m = cam.GetCompositeProjectionTransformMatrix(width / height, -1, 1)
    matrix = [[m.GetElement(i, j) for j in range(4)] for i in range(4)]
    with open(path, "w") as out:
        json.dump({"matrix": matrix, "position": list(cam.GetPosition()),
                   "direction": list(cam.GetDirectionOfProjection()), "size": [width, height],
                   **(extra or {})}, out)


def render_frames(view, reader, prefix, which, width, height, times=None, extra=None):
    """Saves the last frame as PREFIX.png or every frame as PREFIXNNNNNN.png, each with its
    .camera.json (with `extra`, e.g. the point size). `which` = last | all."""
    times = times if times is not None else (list(reader.TimestepValues) or [0.0])
    if save_state(view, times):
        return 0
    chosen = times if which == "all" else times[-1:]
    for k, t in enumerate(chosen):
        view.ViewTime = t
        Render(view)
        name = f"{prefix}{k:06d}" if which == "all" else prefix
        SaveScreenshot(f"{name}.png", view, ImageResolution=[width, height])
        write_camera(view, f"{name}.camera.json", width, height, extra)
    return len(chosen)


def save_state(view, times):
    """With EMERGENT_SAVE_STATE=PATH (scripts/replay), saves the pipeline as a ParaView state
    file at the last time instead of rendering; returns whether it did."""
    path = os.environ.get("EMERGENT_SAVE_STATE")
    if not path:
        return False
    view.ViewTime = times[-1]
    SaveState(path)
    return True


def top_camera(view, lo, hi, width, height):
    """From above (+z looking down), x right, y up."""
    set_camera(view, lo, hi, width, height, (0, 0, -1), up=(0, 1, 0))

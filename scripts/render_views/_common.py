"""Shared by the views (scripts/render_views/*.py): reading a run, a white view with particles as
spheres at their true diameters lit by one light from the camera (a sphere's centre shows exactly
the colour its data maps to, its rim darker), colour maps a check can recompute exactly, walls,
a camera framed on the content beside a strip that holds the legend, a scale bar and the time,
and the frame loop. Every saved image gets a PREFIX.camera.json beside it with the camera's
world-to-screen matrix, pixels per unit length and the strip, so a check (and a user) can find
where any point of the run lands in the picture."""
import json
import os

import h5py
import numpy as np
from paraview.simple import (AddLight, AnnotateTime, Clip, ColorBy, Cylinder, GetActiveViewOrCreate,
                             GetColorTransferFunction, GetOpacityTransferFunction, GetScalarBar, Line,
                             Render, SaveScreenshot, SaveState, Show, Text, Transform,
                             _DisableFirstRenderCameraReset)

# One categorical palette for species and cluster kinds, and the diverging map of signed values
# (blue, light grey, red; interpolated in RGB so a check can recompute a pixel's colour).
SPECIES_RGB = [(0.85, 0.15, 0.10), (0.10, 0.35, 0.85), (0.95, 0.75, 0.10), (0.20, 0.70, 0.25),
               (0.55, 0.25, 0.70), (0.05, 0.75, 0.75)]
DIVERGING = [(-1.0, (0.10, 0.25, 0.90)), (0.0, (0.88, 0.88, 0.88)), (1.0, (0.90, 0.10, 0.10))]
# Temperature, cold to hot (blue, yellow, red).
THERMAL = [(0.0, (0.10, 0.25, 0.90)), (0.5, (0.95, 0.85, 0.20)), (1.0, (0.90, 0.10, 0.10))]
# Walls and containers: neutral grey, so a check tells them from every particle colour.
WALL_GREY = 0.55
# The share of the picture's width on its right that holds the legend, scale bar and time.
STRIP = 0.2
# The unit of length each scene is written in (the label of the scale bar).
UNITS = {"rotating-drum": "d", "vibrated-sawtooth": "d", "granular-bed": "d"}
# The colour maps whose legend annotate() placed: recolouring a frame keeps it shown (a movie
# lost its legend after the first frame when every recolouring hid it).
LEGENDS = set()


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


def sphere_view(width, height):
    """A white view lit by one directional light from the camera (no light kit): a sphere's
    centre faces the light, so it shows exactly its colour; towards its rim it darkens as the
    cosine of its surface's tilt."""
    view = flat_view(width, height)
    view.UseLight = 0
    light = AddLight(view=view)
    light.Coords, light.Type, light.Intensity = "Camera", "Directional", 1.0
    light.Position, light.FocalPoint = [0.0, 0.0, 1.0], [0.0, 0.0, 0.0]
    return view


def spheres(shown, diameter=None):
    """Points drawn as lit spheres (ParaView's Point Gaussian sphere shader) at their true
    diameters: the point array `diameter`, or `diameter` for every point."""
    shown.SetRepresentationType("Point Gaussian")
    shown.ShaderPreset = "Sphere"
    if diameter is None:
        shown.ScaleByArray = 1
        shown.SetScaleArray = ["POINTS", "diameter"]
        shown.UseScaleFunction = 0
        shown.GaussianRadius = 0.5
    else:
        shown.ScaleByArray = 0
        shown.GaussianRadius = diameter / 2
    shown.Ambient, shown.Diffuse, shown.Specular = 0.0, 1.0, 0.0


def diameters(run, group="all", frame=-1):
    """Each particle's diameter at `frame` (1 where the run writes none)."""
    with h5py.File(f"{run}/trajectory.h5", "r") as f:
        g = f[f"particles/{group}"]
        n = g["position/value"].shape[1]
        return np.asarray(g["diameter/value"][frame], float) if "diameter" in g else np.ones(n)


def wall(view, source, opacity=0.25):
    """A wall or container, flat neutral grey, its front faces culled: only the side that faces
    away from the camera is drawn, always behind what it holds."""
    shown = Show(source, view)
    flat(shown)
    shown.ColorArrayName = ["POINTS", ""]
    shown.AmbientColor = shown.DiffuseColor = [WALL_GREY] * 3
    shown.Opacity = opacity
    shown.BackfaceRepresentation = "Cull Frontface"
    return shown


def cylinder_wall(view, radius, z0, z1, opacity=0.25, wedge=None):
    """A cylinder about the z axis from z0 to z1, drawn as wall(); `wedge` (its angle, radians)
    keeps the part between theta = 0 and that angle."""
    body = Cylinder(Radius=radius, Height=z1 - z0, Resolution=256, Capping=0)
    turned = Transform(Input=body)  # the source's axis is y
    turned.Transform.Rotate = [90.0, 0.0, 0.0]
    turned.Transform.Translate = [0.0, 0.0, (z0 + z1) / 2]
    part = turned
    if wedge is not None:
        # Kept: the side each normal points to, y >= 0 and sin(wedge - theta) >= 0.
        for normal in ([0.0, 1.0, 0.0], [float(np.sin(wedge)), float(-np.cos(wedge)), 0.0]):
            part = Clip(Input=part)
            part.ClipType = "Plane"
            part.ClipType.Origin = [0.0, 0.0, 0.0]
            part.ClipType.Normal = normal
            part.Invert = 0
    return wall(view, part, opacity)


def flat(shown):
    """No lighting: a pixel's colour is exactly the colour its data maps to."""
    shown.Ambient, shown.Diffuse, shown.Specular = 1.0, 0.0, 0.0


def flat_points(shown, size):
    """Square points of `size` pixels, unlit."""
    shown.SetRepresentationType("Points")
    shown.PointSize = size
    flat(shown)


def colour_by_value(shown, array, colours, names=None):
    """Colours points by the integer values of a point array, value -> (r, g, b), exactly;
    `names` (value -> text) label them in a legend. Returns the colour map."""
    ColorBy(shown, ("POINTS", array))
    lut = GetColorTransferFunction(array)
    lut.InterpretValuesAsCategories = 1
    lut.Annotations = sum(([str(v), str(names.get(v, v) if names else v)] for v in colours), [])
    lut.IndexedColors = sum((list(colours[v]) for v in colours), [])
    return lut


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
    shown.SetScalarBarVisibility(GetActiveViewOrCreate("RenderView"), lut.GetGlobalIDAsString() in LEGENDS)
    return lut


def frame_content(view, points, width, height, direction, up=None, strip=STRIP, pad=0.0):
    """An orthographic camera looking along `direction` whose picture left of the strip (its
    right `strip` share of the width) is filled by the content, 3 % to spare: `points` [n, 3]
    (e.g. sphere centres, container outlines, a box's corners()), each reaching `pad` further.
    Returns the framing for annotate()."""
    _DisableFirstRenderCameraReset()
    d = np.asarray(direction, float) / np.linalg.norm(direction)
    points = np.asarray(points, float)
    up, right = view_axes(d, up)
    u, v = points @ right, points @ up
    half_w, half_h = np.ptp(u) / 2 + pad, np.ptp(v) / 2 + pad
    centre = (u.min() + u.max()) / 2 * right + (v.min() + v.max()) / 2 * up + (points @ d).mean() * d
    content_width = width * (1 - strip)
    scale = max(half_h, half_w * height / content_width) * 1.03
    focal = centre + right * (strip * width * scale / height)
    view.CameraParallelProjection = 1
    view.CameraFocalPoint = list(focal)
    view.CameraPosition = list(focal - d * 10 * (np.ptp(points, axis=0).max() + 2 * pad + 1))
    view.CameraViewUp = list(up)
    view.CameraParallelScale = scale
    return {"focal": focal, "right": right, "up": up, "scale": scale, "width": width, "height": height,
            "strip": strip, "pixels_per_unit": height / (2 * scale)}


def view_axes(d, up=None):
    """Up and right vectors of a view along the unit vector d."""
    if up is None:
        up = (0, 1, 0) if abs(d[1]) < 0.9 else (0, 0, 1)
    up = np.asarray(up, float)
    up = up - d * (up @ d)
    up /= np.linalg.norm(up)
    return up, np.cross(d, up)


def nice_length(limit):
    """The largest 1, 2 or 5 times a power of ten not above `limit`."""
    power = 10.0 ** np.floor(np.log10(limit))
    return max(m * power for m in (1, 2, 5) if m * power <= limit)


def annotate(view, framing, unit, lut=None, title="", time=True):
    """In the strip: the colour legend of `lut` (categories or a range) with `title`, a scale bar
    (a world line of a round length, labelled with `unit`) and the time (t in the run's time
    unit). Black on white, the text in the strip only. Returns what the camera file records."""
    width, height, strip = framing["width"], framing["height"], framing["strip"]
    left = 1 - strip
    font = max(8, min(14, int(strip * width / 9)))  # "t = 1234.5 tau" fits the strip
    if lut is not None:
        LEGENDS.add(lut.GetGlobalIDAsString())
        bar = GetScalarBar(lut, view)
        bar.Title, bar.ComponentTitle = title, ""
        bar.WindowLocation = "Any Location"
        bar.Position = [left + 0.03, 0.5]
        bar.ScalarBarLength = 0.4
        bar.HorizontalTitle = 1
        # The text right of the bar, in the strip: a category's name, or a range's ticks.
        categories = bool(lut.InterpretValuesAsCategories)
        bar.TextPosition = ("Ticks left/bottom, annotations right/top" if categories
                            else "Ticks right/top, annotations left/bottom")
        bar.AutomaticLabelFormat, bar.LabelFormat, bar.RangeLabelFormat = 0, "%-#.3g", "%-#.3g"
        bar.TitleColor = bar.LabelColor = [0.0, 0.0, 0.0]
        bar.TitleFontSize = bar.LabelFontSize = font
        bar.Visibility = 1
    # The scale bar, on the picture's focal plane, centred in the strip at 30 % of the height
    # (its label below it).
    pixels = framing["pixels_per_unit"]
    length = nice_length(0.6 * strip * width / pixels)
    centre = (framing["focal"] + framing["right"] * ((1 - strip / 2) * width - width / 2) / pixels
              - framing["up"] * (0.2 * height) / pixels)
    half = framing["right"] * length / 2
    shown = Show(Line(Point1=list(centre - half), Point2=list(centre + half)), view)
    flat(shown)
    shown.ColorArrayName = ["POINTS", ""]
    shown.AmbientColor = shown.DiffuseColor = [0.0, 0.0, 0.0]
    shown.LineWidth = 3
    label = Show(Text(Text=f"{length:g} {unit}"), view)
    label.WindowLocation = "Any Location"
    label.Position = [left + 0.02, 0.22]
    label.Color, label.FontSize = [0.0, 0.0, 0.0], font
    if time:
        clock = AnnotateTime()
        clock.Format = "t = {time:.1f}" + (" tau" if unit == "sigma" else "")
        shown = Show(clock, view)
        shown.WindowLocation = "Any Location"
        shown.Position = [left + 0.02, 0.06]
        shown.Color, shown.FontSize = [0.0, 0.0, 0.0], font
    return {"strip": [int(np.floor(left * width)), 0, width, height], "pixels_per_unit": pixels,
            "scale_bar": length}


def framed(view, run, points, width, height, direction, up=None, lut=None, title="", pad=0.0):
    """frame_content() and annotate() in one, the scene's unit on the scale bar."""
    framing = frame_content(view, points, width, height, direction, up, pad=pad)
    return annotate(view, framing, UNITS.get(scene(run), "sigma"), lut, title)


def corners(lo, hi):
    """The eight corners of the box [lo, hi]."""
    return np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])], float)


def ring(radius, z, n=128, angle=2 * np.pi):
    """Points on a circle about the z axis at height z (an arc of `angle` from theta = 0)."""
    theta = np.linspace(0, angle, n)
    return np.c_[radius * np.cos(theta), radius * np.sin(theta), np.full(n, z)]


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


def render_frames(view, reader, prefix, which, width, height, times=None, extra=None, at_time=None):
    """Saves the last frame as PREFIX.png or every frame as PREFIXNNNNNN.png, each with its
    .camera.json (with `extra`, e.g. the point size). `which` = last | all. `at_time(t)`, where
    given, moves what the data does not hold (a vibrating base) to time t before each frame."""
    times = times if times is not None else (list(reader.TimestepValues) or [0.0])
    if at_time is not None:
        at_time(times[-1])
    if save_state(view, times):
        return 0
    chosen = times if which == "all" else times[-1:]
    for k, t in enumerate(chosen):
        view.ViewTime = t
        if at_time is not None:
            at_time(t)
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

"""Shared by the granular views (cutaway, section, big_grains, small_grains): rotating-drum and
vibrated-sawtooth runs, big grains (species 1) red and small (species 0) yellow as in the paper,
spheres at their true diameters, the container drawn behind them (the drum's wall, translucent,
or its circle in the section; the sawtooth's base where its vibration has it in each frame),
framed on the container, with the legend, a scale bar and the time."""
import os
import sys

import h5py
import numpy as np
from paraview.simple import (Calculator, LinearExtrusion, PolyLineSource, Show, Threshold, Transform,
                             Xdmf3ReaderT)

# The section view: the drum's grains within this distance of its middle cross-section.
SECTION_HALF_THICKNESS = 1.5

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _common import (SPECIES_RGB, WALL_GREY, box, colour_by_value, corners, cylinder_wall, diameters,  # noqa: E402
                     flat, framed, parameter, render_frames, ring, scene, sphere_view, spheres, wall)

BIG_RGB, SMALL_RGB = SPECIES_RGB[0], SPECIES_RGB[2]
SCENES = ("rotating-drum", "vibrated-sawtooth")


def keep(source, function, lower, upper, name):
    """Points whose `function` (a Calculator expression) lies in [lower, upper]."""
    calc = Calculator(Input=source)
    calc.ResultArrayName = name
    calc.Function = function
    kept = Threshold(Input=calc)
    kept.Scalars = ["POINTS", name]
    try:
        kept.LowerThreshold, kept.UpperThreshold = lower, upper
    except AttributeError:
        kept.ThresholdRange = [lower, upper]
    return kept


def text(run, name):
    with h5py.File(f"{run}/trajectory.h5", "r") as f:
        value = f["parameters"].attrs[name]
    return value.decode() if isinstance(value, bytes) else str(value)


def sawtooth_base(view, run, lo, hi, y0, y1):
    """The base's profile through its rods' centres, teeth of tooth_period and tooth_height along
    x (gentle edge rising toward +x over gentle_fraction of the period; `mirrored` reflected;
    `flat` level), from y0 to y1, and a function of time that moves it to its level
    z_b(t) = amplitude sin(2 pi frequency t); None for the cylindrical container, whose rings
    are not drawn."""
    if text(run, "container") != "slot":
        return None
    period, height = parameter(run, "tooth_period"), parameter(run, "tooth_height")
    gentle, kind = parameter(run, "gentle_fraction"), text(run, "base")
    peak = {"sawtooth": gentle, "mirrored": 1 - gentle}.get(kind)
    points = []
    for k in range(int(round((hi[0] - lo[0]) / period))):
        start = lo[0] + k * period
        points += [(start, 0.0)] + ([(start + peak * period, height)] if peak is not None else [])
    points.append((hi[0], 0.0))
    line = PolyLineSource(Points=sum(([u, y0, z] for u, z in points), []))
    surface = LinearExtrusion(Input=line)
    surface.Vector, surface.ScaleFactor, surface.Capping = [0.0, 1.0, 0.0], y1 - y0, 0
    moved = Transform(Input=surface)
    shown = wall(view, moved, opacity=1.0)
    shown.BackfaceRepresentation = "Follow Frontface"  # seen from above: drawn both sides, opaque
    amplitude, frequency = parameter(run, "amplitude"), parameter(run, "frequency")

    def at_time(t):
        moved.Transform.Translate = [0.0, 0.0, amplitude * float(np.sin(2 * np.pi * frequency * t))]

    return at_time


def draw(mode):
    """mode: cutaway (the near half removed: x > 0 in the drum, the front y < middle in the
    sawtooth's container), section (the drum's grains within SECTION_HALF_THICKNESS of its
    middle cross-section, seen along the axis inside the wall's circle) or big / small (that
    species alone: the drum from the side, the sawtooth layer from above)."""
    run, prefix, which, width, height = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), int(sys.argv[5])
    drum = scene(run) == "rotating-drum"
    lo, hi = box(run, "all")
    with h5py.File(f"{run}/trajectory.h5", "r") as f:
        x = f["particles/all/position/value"][-1]
        species = f["particles/all/species/value"][-1]
    d = diameters(run)
    reader = Xdmf3ReaderT(FileName=[f"{run}/trajectory.xmf"])
    view = sphere_view(width, height)
    middle = (lo[1] + hi[1]) / 2
    if mode == "section":
        middle_z = (lo[2] + hi[2]) / 2
        shown = keep(reader, f"abs(coordsZ-({middle_z!r}))", 0.0, SECTION_HALF_THICKNESS, "slab")
        direction, up = (0, 0, -1), (0, 1, 0)
        chosen = np.abs(x[:, 2] - middle_z) <= SECTION_HALF_THICKNESS
    elif mode == "cutaway":
        if drum:
            shown, direction, up = keep(reader, "coordsX", -1e30, 0.0, "cut"), (-1, -0.45, -0.35), (0, 1, 0)
            chosen = x[:, 0] <= 0
        else:
            shown = keep(reader, f"coordsY-({middle!r})", 0.0, 1e30, "cut")
            direction, up = (0.3, 1, -0.5), (0, 0, 1)
            chosen = x[:, 1] >= middle
    else:
        k = 1 if mode == "big" else 0
        shown = keep(reader, "species", k - 0.5, k + 0.5, "chosen")
        direction, up = ((-1, 0, 0), (0, 1, 0)) if drum else ((0, 0, -1), (0, 1, 0))
        chosen = species == k
    at_time = None
    if drum and mode == "section":
        radius = parameter(run, "diameter") / 2
        content = ring(radius, middle_z, n=256)
        circle = Show(PolyLineSource(Points=list(content.ravel()), Closed=1), view)  # the wall, edge on
        flat(circle)
        circle.ColorArrayName = ["POINTS", ""]
        circle.AmbientColor = circle.DiffuseColor = [WALL_GREY] * 3
        circle.LineWidth = 2
        pad = 0.0
    elif drum:
        radius = parameter(run, "diameter") / 2
        cylinder_wall(view, radius, lo[2], hi[2])
        content = np.concatenate([ring(radius, z) for z in (lo[2], hi[2])])  # the drum, wall and all
        pad = 0.0
    else:
        y0 = middle if mode == "cutaway" else lo[1]
        at_time = sawtooth_base(view, run, lo, hi, y0, hi[1])
        # The grains shown and the base under them, at either end of its swing.
        swing = parameter(run, "amplitude")
        base = corners([lo[0], y0, -swing - 0.5], [hi[0], hi[1], parameter(run, "tooth_height") + swing])
        content = np.concatenate([x[chosen], base])
        pad = d[chosen].max() / 2 if chosen.any() else 0.0
    out = Show(shown, view)
    spheres(out)
    lut = colour_by_value(out, "species", {0: SMALL_RGB, 1: BIG_RGB}, {0: "small", 1: "big"})
    camera = framed(view, run, content, width, height, direction, up, lut, "grains", pad=pad)
    n = render_frames(view, reader, prefix, which, width, height, extra=camera, at_time=at_time)
    print(f"{n} image(s) of {run}")

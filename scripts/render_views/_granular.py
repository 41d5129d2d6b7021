"""Shared by the granular views (cutaway, big_grains, small_grains): rotating-drum and
vibrated-sawtooth runs, big grains (species 1) red and small (species 0) yellow as in the paper,
flat-shaded square points the size of a small grain."""
import os
import sys

from paraview.simple import Calculator, Show, Threshold, Xdmf3ReaderT

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _common import (SPECIES_RGB, box, colour_by_value, flat_points, flat_view, parameter,  # noqa: E402
                     point_size, render_frames, scene, set_camera)

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


def draw(mode):
    """mode: cutaway (the near half removed: x > 0 in the drum, the front y < middle in the
    sawtooth's container) or big / small (that species alone: the drum from the side, the
    sawtooth layer from above)."""
    run, prefix, which, width, height = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), int(sys.argv[5])
    name = scene(run)
    lo, hi = box(run, "all")
    drum = name == "rotating-drum"
    reader = Xdmf3ReaderT(FileName=[f"{run}/trajectory.xmf"])
    if mode == "cutaway":
        if drum:
            shown, direction, up = keep(reader, "coordsX", -1e30, 0.0, "cut"), (-1, -0.45, -0.35), (0, 1, 0)
        else:
            middle = (lo[1] + hi[1]) / 2
            shown = keep(reader, f"coordsY-({middle!r})", 0.0, 1e30, "cut")
            direction, up = (0.3, 1, -0.5), (0, 0, 1)
        diameter = 1.0
    else:
        k = 1 if mode == "big" else 0
        shown = keep(reader, "species", k - 0.5, k + 0.5, "chosen")
        direction, up = ((-1, 0, 0), (0, 1, 0)) if drum else ((0, 0, -1), (0, 1, 0))
        diameter = 1.0 if drum else parameter(run, "d_big" if k == 1 else "d_small") - 0.1
    if not drum:  # the layer, not the empty space above it
        hi = hi.copy()
        hi[2] = min(hi[2], lo[2] + 3 + 4 * parameter(run, "depth"))
    view = flat_view(width, height)
    out = Show(shown, view)
    size = point_size(lo, hi, width, height, diameter, direction)
    flat_points(out, size)
    colour_by_value(out, "species", {0: SMALL_RGB, 1: BIG_RGB})
    set_camera(view, lo, hi, width, height, direction, up)
    n = render_frames(view, reader, prefix, which, width, height, extra={"point_size": size})
    print(f"{n} image(s) of {run}")

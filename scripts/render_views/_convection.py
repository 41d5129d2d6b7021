"""Shared by the convection views: rayleigh-benard's flow as stream lines of the coarse-grained
velocity (the run's `fields.grid` box grid, cell averages interpolated to the grid's nodes),
started from 200 points spread through the layer, coloured by the local temperature (blue cold,
yellow, red hot over the frame's range of cell temperatures), flat-shaded, orthographic, framed
on the layer beside the strip with the temperature scale, a scale bar and the time. The stream
lines' points and temperatures are saved beside each image (PREFIX.lines.csv). A continued run
is read across its segments (fields, then fields.from<STEP> in order): a still shows the last
segment's last frame, a movie every frame once."""
import os
import sys

import h5py
import numpy as np
from paraview.simple import (CellDatatoPointData, ExtractBlock, Hide, MergeBlocks, Render, SaveData,
                             SaveScreenshot, Show, StreamTracer, Xdmf3ReaderT)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # scripts/: emergentpy
from emergentpy import Run  # noqa: E402
from _common import (THERMAL, annotate, colour_by_range, corners, flat, flat_view, frame_content,  # noqa: E402
                     save_state, write_camera)

DIRECTIONS = {"above": ((0, 0, -1), (0, 1, 0)), "below": ((0, 0, 1), (0, 1, 0)),
              "oblique": ((-0.6, -1.0, -0.8), (0, 0, 1))}
LINE_WIDTH = 3


def segments(run):
    """The run's fields files without their extension, in order (the first run's, then each
    continuation's), as emergentpy reads a continued run."""
    return [path[:-len(".h5")] for path in Run(run).fields_paths]


def draw(side):
    run, prefix, which, width, height = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), int(sys.argv[5])
    parts = segments(run) if which == "all" else segments(run)[-1:]
    with h5py.File(f"{parts[0]}.h5", "r") as f:
        g = f["fields/box"]
        lo, hi = np.array(g.attrs["lo"], float), np.array(g.attrs["hi"], float)
    view = flat_view(width, height)

    def stream_lines(part):
        """The pipeline from one segment's fields to its stream lines, shown in the view (a
        reader handed another file keeps the first one's times: each segment has its own)."""
        reader = Xdmf3ReaderT(FileName=[f"{part}.xmf"])
        # The reader gives every grid of fields.xmf as one block each; the scene's own grids (the
        # convection scene's slice and profile) overlap the box grid, always the first block.
        box_grid = ExtractBlock(Input=reader)
        box_grid.Selectors = ["/Root/Block0"]
        nodes = CellDatatoPointData(Input=MergeBlocks(Input=box_grid))
        lines = StreamTracer(Input=nodes, SeedType="Point Cloud")
        lines.Vectors = ["POINTS", "velocity"]
        lines.SeedType.Center = list((lo + hi) / 2)
        lines.SeedType.Radius = 0.49 * float(np.min(hi - lo))
        lines.SeedType.NumberOfPoints = 200
        lines.MaximumStreamlineLength = float(4 * np.linalg.norm(hi - lo))
        lines.IntegrationStepUnit = "Cell Length"
        lines.InitialStepLength = 0.1
        lines.MaximumStepLength = 0.1
        shown = Show(lines, view)
        shown.LineWidth = LINE_WIDTH
        flat(shown)
        return reader, lines, shown

    direction, up = DIRECTIONS[side]
    framing = frame_content(view, corners(lo, hi), width, height, direction, up)
    strip = None
    k = 0
    done = -np.inf  # the last time drawn: a continuation may repeat its first frame
    shown = None
    for part in parts:
        if shown is not None:
            Hide(lines, view)
        reader, lines, shown = stream_lines(part)
        with h5py.File(f"{part}.h5", "r") as f:
            temperature = f["fields/box/temperature/value"][:]
        times = list(reader.TimestepValues) or [0.0]
        if os.environ.get("EMERGENT_SAVE_STATE"):
            t_lo, t_hi = float(np.nanmin(temperature[-1])), float(np.nanmax(temperature[-1]))
            colour_by_range(shown, "POINTS", "temperature", THERMAL, t_lo, max(t_hi, t_lo + 1e-12))
            save_state(view, times)
            return
        frames = range(len(times)) if which == "all" else [len(times) - 1]
        for frame in frames:
            if times[frame] <= done:
                continue
            done = times[frame]
            t_lo, t_hi = float(np.nanmin(temperature[frame])), float(np.nanmax(temperature[frame]))
            lut = colour_by_range(shown, "POINTS", "temperature", THERMAL, t_lo, max(t_hi, t_lo + 1e-12))
            if strip is None:
                strip = annotate(view, framing, "sigma", lut, "temperature")
            view.ViewTime = times[frame]
            Render(view)
            name = f"{prefix}{k:06d}" if which == "all" else prefix
            SaveScreenshot(f"{name}.png", view, ImageResolution=[width, height])
            write_camera(view, f"{name}.camera.json", width, height,
                         {**strip, "line_width": LINE_WIDTH, "temperature_range": [t_lo, t_hi]})
            if which != "all":
                SaveData(f"{name}.lines.csv", proxy=lines, PointDataArrays=["temperature"])
            k += 1
    print(f"{k} image(s) of {run}")

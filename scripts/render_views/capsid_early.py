"""Run by pvbatch (scripts/render): capsid-assembly's early state as the paper shows it (the
second recorded frame, the first after the start, whose solvent is still a lattice; the first
when there is one frame only): the capsomers' spheres (species 1) as opaque blue spheres at their
true diameter lit from the camera, the solvent atoms (species 0) as small flat semitransparent
grey points (30 % opaque), the attraction sites hidden; from above, orthographic, framed on the
box, with a scale bar and the time. With --movie, every frame.
usage: pvbatch capsid_early.py RUN_DIR OUT_PREFIX all|last WIDTH HEIGHT"""
import os
import sys

from paraview.simple import Show, Threshold, Xdmf3ReaderT

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _common import (SPECIES_RGB, box, corners, flat_points, framed, render_frames, sphere_view,  # noqa: E402
                     spheres)

SOLVENT_GREY, SOLVENT_OPACITY, SOLVENT_SCALE = 0.5, 0.3, 0.3


def species(source, k):
    kept = Threshold(Input=source)
    kept.Scalars = ["POINTS", "species"]
    try:
        kept.LowerThreshold, kept.UpperThreshold = k - 0.5, k + 0.5
    except AttributeError:
        kept.ThresholdRange = [k - 0.5, k + 0.5]
    return kept


run, prefix, which, width, height = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), int(sys.argv[5])
lo, hi = box(run, "all")
reader = Xdmf3ReaderT(FileName=[f"{run}/trajectory.xmf"])
view = sphere_view(width, height)
capsomers = Show(species(reader, 1), view)
spheres(capsomers, 1.0)
capsomers.ColorArrayName = ["POINTS", ""]
capsomers.AmbientColor = capsomers.DiffuseColor = list(SPECIES_RGB[1])
camera = framed(view, run, corners(lo, hi), width, height, (0, 0, -1), (0, 1, 0))
solvent = Show(species(reader, 0), view)
solvent_size = max(2, int(round(camera["pixels_per_unit"] * SOLVENT_SCALE)))
flat_points(solvent, solvent_size)
solvent.ColorArrayName = ["POINTS", ""]
solvent.AmbientColor = solvent.DiffuseColor = [SOLVENT_GREY] * 3
solvent.Opacity = SOLVENT_OPACITY
times = list(reader.TimestepValues) or [0.0]
n = render_frames(view, reader, prefix, which, width, height, times=times if which == "all" else times[1:2] or times[:1],
                  extra={**camera, "solvent_point_size": solvent_size})
print(f"{n} image(s) of {run}")

"""Run by pvbatch (scripts/render): capsid-assembly's early state as the paper shows it (the
second recorded frame, the first after the start, whose solvent is still a lattice; the first
when there is one frame only): the capsomers' spheres (species 1) opaque blue, the solvent atoms (species 0) as small
semitransparent grey points (30 % opaque), the attraction sites hidden; from above, orthographic,
flat-shaded. With --movie, every frame.
usage: pvbatch capsid_early.py RUN_DIR OUT_PREFIX all|last WIDTH HEIGHT"""
import os
import sys

from paraview.simple import Show, Threshold, Xdmf3ReaderT

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _common import SPECIES_RGB, box, flat_points, flat_view, point_size, render_frames, top_camera  # noqa: E402

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
view = flat_view(width, height)
size = point_size(lo, hi, width, height, 1.0, (0, 0, -1))
spheres = Show(species(reader, 1), view)
flat_points(spheres, size)
spheres.ColorArrayName = ["POINTS", ""]
spheres.AmbientColor = spheres.DiffuseColor = list(SPECIES_RGB[1])
solvent = Show(species(reader, 0), view)
solvent_size = max(2, int(round(size * SOLVENT_SCALE)))
flat_points(solvent, solvent_size)
solvent.ColorArrayName = ["POINTS", ""]
solvent.AmbientColor = solvent.DiffuseColor = [SOLVENT_GREY] * 3
solvent.Opacity = SOLVENT_OPACITY
top_camera(view, lo, hi, width, height)
times = list(reader.TimestepValues) or [0.0]
n = render_frames(view, reader, prefix, which, width, height, times=times if which == "all" else times[1:2] or times[:1],
                  extra={"point_size": size, "solvent_point_size": solvent_size})
print(f"{n} image(s) of {run}")

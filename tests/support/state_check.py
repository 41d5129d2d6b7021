"""Run by pvbatch: loads a state file from scripts/replay and checks that it opens the run: its
reader has the run's recorded times and, at the last, the run's particle (or field-cell) count,
and what the view shows from the run (walls, labels and legends aside) has the number of points
the view's rule gives (every particle; the drum's cut-away: those with x <= 0; capsid: capsomers
in clusters; stream lines: some).
usage: pvbatch state_check.py STATE.pvsm RUN_DIR VIEW"""
import sys

import h5py
import numpy as np
from paraview import servermanager
from paraview.simple import GetActiveViewOrCreate, GetSources, LoadState

state, run, view_name = sys.argv[1], sys.argv[2], sys.argv[3]
LoadState(state)
view = GetActiveViewOrCreate("RenderView")
sources = GetSources()
readers = [p for (name, _), p in sources.items() if "Reader" in p.GetXMLName()]
if len(readers) != 1:
    sys.exit(f"FAIL: {len(readers)} readers in the state")
reader = readers[0]
times = list(reader.TimestepValues)
group = "bodies" if view_name == "capsid" else "all"  # the capsid view reads the bodies' sidecar
with h5py.File(f"{run}/trajectory.h5", "r") as f:
    frames = len(f[f"particles/{group}/position/step"])
    x = f[f"particles/{group}/position/value"][-1]
    csize = f["particles/bodies/cluster_size/value"][-1] if view_name == "capsid" else None
fields = view_name.startswith("convection_")
if fields:
    with h5py.File(f"{run}/fields.h5", "r") as f:  # every grid's nodes, one block each
        frames = len(f["fields/box/velocity/step"])
        expected = sum(int(np.prod(np.array(g.attrs["shape"]) + 1)) for g in f["fields"].values())
else:
    expected = len(x)
if len(times) != frames:
    sys.exit(f"FAIL: the state's reader has {len(times)} times, the run {frames} frames")
reader.UpdatePipeline(times[-1])
n = servermanager.Fetch(reader).GetNumberOfPoints()
if n != expected:
    sys.exit(f"FAIL: the state's reader has {n} points at the last time, the run {expected}")
def reads_the_run(proxy):
    """Whether the pipeline object draws from the run's reader (not a wall, a label or a scale
    bar the view adds)."""
    while proxy is not None:
        if proxy == reader:
            return True
        inputs = proxy.ListProperties()
        proxy = proxy.Input if "Input" in inputs else None
        if isinstance(proxy, list):
            proxy = proxy[0] if proxy else None
    return False


counts = []
for rep in view.Representations:
    source = rep.Input if "Input" in rep.ListProperties() else None
    if rep.Visibility == 1 and source is not None and reads_the_run(source):
        source.UpdatePipeline(times[-1])
        counts.append(servermanager.Fetch(source).GetNumberOfPoints())
if not counts:
    sys.exit("FAIL: nothing shown")
if view_name == "cutaway" and counts != [int(np.sum(x[:, 0] <= 0))]:
    sys.exit(f"FAIL: the cut-away shows {counts} points, the run has {int(np.sum(x[:, 0] <= 0))} with x <= 0")
if view_name == "particles" and counts != [len(x)]:
    sys.exit(f"FAIL: shows {counts} points, the run has {len(x)}")
if view_name == "capsid" and counts != [int(np.sum(csize >= 2))]:
    sys.exit(f"FAIL: shows {counts} capsomers, the run has {int(np.sum(csize >= 2))} in clusters")
if min(counts) < 1:
    sys.exit(f"FAIL: a shown object is empty ({counts})")
print(f"ok: the state opens the run ({len(times)} times, {n} points), shows {counts} points")

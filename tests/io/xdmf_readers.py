"""Run by pvpython: each ParaView XDMF reader opens a run's trajectory.xmf (the particles) and
trajectory.bodies.xmf (rigid bodies, where the run has them) and shows what the H5MD file holds
(they fail silently, so the content is checked): the number of time steps, the points and cells,
the arrays, and the values at the last step against h5py's reading of the same file.
usage: pvpython xdmf_readers.py RUN_DIR"""
import sys

import h5py
import numpy as np
from paraview import servermanager
from paraview.simple import Xdmf3ReaderS, Xdmf3ReaderT, XDMFReader
from vtk.numpy_interface import dataset_adapter as dsa

run = sys.argv[1]
f = h5py.File(f"{run}/trajectory.h5", "r")
groups = {g: f["particles"][g] for g in f["particles"]}
frames = {g: len(groups[g]["position/value"]) for g in groups}
expected_arrays = {g: sorted(e for e in groups[g]["frames"] if e != "position") for g in groups}
n_points = {g: groups[g]["position/value"].shape[1] for g in groups}


def leaves(data):
    """(block name, dataset) of every leaf of what the reader made."""
    if data.IsA("vtkMultiBlockDataSet"):
        out = []
        for b in range(data.GetNumberOfBlocks()):
            name = data.GetMetaData(b).Get(data.NAME()) if data.HasMetaData(b) else str(b)
            out += [(name, d) for _, d in leaves(data.GetBlock(b))]
        return out
    return [("", data)]


bad = []
for make, g in [(m, g) for m in (XDMFReader, Xdmf3ReaderS, Xdmf3ReaderT) for g in groups]:
    name = make.__name__ + (" (bodies)" if g == "bodies" else "")
    path = f"{run}/trajectory.xmf" if g == "all" else f"{run}/trajectory.bodies.xmf"
    reader = make(FileNames=[path]) if make is XDMFReader else make(FileName=[path])
    steps = list(reader.TimestepValues) if reader.TimestepValues else []
    want_steps = frames[g]
    if len(steps) != want_steps:
        bad.append(f"{name}: {len(steps)} time steps, the file has {want_steps} frames")
        continue
    reader.UpdatePipeline(steps[-1])
    blocks = leaves(servermanager.Fetch(reader))
    for _ in (0,):
        found = [d for _, d in blocks if d is not None and d.GetNumberOfPoints() == n_points[g]]
        if not found:
            bad.append(f"{name}: no block with the {n_points[g]} points of /particles/{g} "
                       f"(blocks: {[d.GetNumberOfPoints() if d else None for _, d in blocks]})")
            continue
        d = dsa.WrapDataObject(found[0])
        cells = found[0].GetNumberOfCells()
        if cells != n_points[g]:
            bad.append(f"{name}: /particles/{g} has {cells} cells for {n_points[g]} points")
        arrays = sorted(d.PointData.keys())
        if arrays != expected_arrays[g]:
            bad.append(f"{name}: /particles/{g} arrays {arrays}, expected {expected_arrays[g]}")
        last = frames[g] - 1
        if not np.allclose(np.asarray(d.Points), groups[g]["position/value"][last]):
            bad.append(f"{name}: /particles/{g} positions at the last step differ from the file's")
        for e in expected_arrays[g]:
            if e in arrays:
                mine = np.asarray(d.PointData[e]).reshape(groups[g][f"{e}/value"][last].shape)
                if not np.allclose(mine, groups[g][f"{e}/value"][last]):
                    bad.append(f"{name}: /particles/{g} array {e} differs from the file's")
    print(f"{name}: {len(steps)} steps, {n_points[g]} points, arrays {expected_arrays[g]}")
if bad:
    print("\n".join("FAIL: " + b for b in bad))
    sys.exit(1)
print("ok: every XDMF reader shows the trajectory as the file holds it")

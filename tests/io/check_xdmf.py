#!/usr/bin/python3
"""Validates an XDMF sidecar: well-formed XML, a temporal collection per grid, and every HDF
DataItem pointing at an existing dataset of the stated shape. With pvpython on the PATH, also
opens it with ParaView's XDMF reader and checks the cell count and arrays.

usage: check_xdmf.py DIR/fields.xmf EXPECTED_FRAMES
"""
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

import h5py

path, frames = sys.argv[1], int(sys.argv[2])
failures = []
root = ET.parse(path).getroot()  # raises on malformed XML
folder = os.path.dirname(os.path.abspath(path))
collections = root.findall("./Domain/Grid[@CollectionType='Temporal']")
if not collections:
    failures.append("no temporal collection")
for collection in collections:
    steps = collection.findall("Grid")
    if len(steps) != frames:
        failures.append(f"{collection.get('Name')}: {len(steps)} time steps, expected {frames}")
    times = [float(g.find("Time").get("Value")) for g in steps]
    if times != sorted(times) or len(set(times)) != len(times):
        failures.append("times not strictly increasing")
    for item in collection.iter("DataItem"):
        if item.get("Format") != "HDF":
            continue
        file_name, dataset = item.text.strip().split(":", 1)
        dims = tuple(int(d) for d in item.get("Dimensions").split())
        with h5py.File(os.path.join(folder, file_name), "r") as f:
            if dataset not in f:
                failures.append(f"missing dataset {dataset}")
            elif f[dataset].shape != dims:
                failures.append(f"{dataset}: shape {f[dataset].shape}, XDMF says {dims}")
            elif not (f[dataset][()] == f[dataset][()]).any():
                failures.append(f"{dataset}: all NaN")

pvpython = shutil.which("pvpython")
if pvpython and not failures:
    script = f"""
from paraview.simple import XDMFReader, UpdatePipeline
r = XDMFReader(FileNames=[{path!r}])
r.UpdatePipelineInformation()
n_times = len(r.TimestepValues) if hasattr(r.TimestepValues, '__len__') else 1
UpdatePipeline(proxy=r)
info = r.GetDataInformation()
arrays = [r.CellData.GetArray(i).Name for i in range(len(r.CellData))]
print(n_times, info.GetNumberOfCells(), ' '.join(sorted(arrays)))
"""
    out = subprocess.run([pvpython, "-c", script], capture_output=True, text=True)
    words = out.stdout.split()
    if out.returncode != 0 or len(words) < 3 or int(words[0]) != frames or int(words[1]) == 0 \
            or "density" not in words:
        failures.append(f"ParaView could not read it: {out.stdout.strip()} {out.stderr.strip()[-300:]}")
    else:
        print(f"ParaView XDMFReader: {words[0]} time steps, {words[1]} cells, arrays {words[2:]}")
elif not pvpython:
    print("pvpython not installed: ParaView check skipped (structure checked with h5py)")

if failures:
    print("\n".join("FAIL: " + m for m in failures))
    sys.exit(1)
print(f"ok: {path} is valid XDMF with {frames} frames per grid")

#!/usr/bin/python3
"""Checks a run's snapshot.h5 (the watch snapshot) against the run's own files: every field
grid's frame equals the last frame of fields.h5 exactly, the last value of every measure equals
the last sample of the same observable in trajectory.h5, every history sample (each component of
a short vector's) equals the run's own at its step, histories are increasing in step and at most
2048 long, and the snapshot is marked final at the run's last step.
usage: snapshot_check.py RUN_DIR [MIN_HISTORY]"""
import sys

import h5py
import numpy as np

run = sys.argv[1]
min_history = int(sys.argv[2]) if len(sys.argv) > 2 else 1
s = h5py.File(f"{run}/snapshot.h5", "r")
t = h5py.File(f"{run}/trajectory.h5", "r")
problems = []
last_step = int(t["observables/temperature/step"][-1])
if int(s.attrs["final"]) != 1 or int(s.attrs["step"]) < last_step:
    problems.append(f"snapshot at step {s.attrs['step']} final={s.attrs['final']}, run's last sample {last_step}")
fields = 0
try:
    fh = h5py.File(f"{run}/fields.h5", "r")
except OSError:
    fh = None
for grid in s["fields"]:
    for q in ("density", "velocity", "temperature", "count"):
        want = fh[f"fields/{grid}/{q}/value"][-1]
        if not np.array_equal(s[f"fields/{grid}/{q}"][:], want):
            problems.append(f"fields/{grid}/{q} differs from the last frame of fields.h5")
        fields += 1
    if fh is not None and list(fh["fields"][grid].attrs["shape"]) != list(s["fields"][grid].attrs["shape"]):
        problems.append(f"fields/{grid}: shape attribute differs")
if fh is not None and set(fh["fields"]) != set(s["fields"]):
    problems.append(f"grids {sorted(s['fields'])} in the snapshot, {sorted(fh['fields'])} in fields.h5")
measures = 0
for name in s["latest"]:
    if name not in t["observables"]:
        problems.append(f"latest/{name} is no observable of the run")
        continue
    if not np.array_equal(np.ravel(s["latest"][name][:]), np.ravel(t[f"observables/{name}/value"][-1]), equal_nan=True):
        problems.append(f"latest/{name} differs from the run's last {name}")
    measures += 1
longest = vectors = 0
for name in s["measures"]:
    step = s[f"measures/{name}/step"][:]
    longest = max(longest, len(step))
    if len(step) > 2048 or np.any(np.diff(step) <= 0):
        problems.append(f"measures/{name}: {len(step)} samples or steps not increasing")
    obs = t[f"observables/{name}"]
    k = np.searchsorted(obs["step"][:], step)
    history = s[f"measures/{name}/value"][:]
    recorded = obs["value"][:].reshape(len(obs["step"]), -1)[k]  # every component of a short vector
    if np.any(obs["step"][:][k] != step) or not np.array_equal(recorded, history.reshape(len(step), -1),
                                                                equal_nan=True):
        problems.append(f"measures/{name}: a sample differs from the run's {name} at its step")
    vectors += history.ndim == 2
if longest < min_history or measures == 0:
    problems.append(f"histories up to {longest} samples (want >= {min_history}), {measures} measures")
if problems:
    sys.exit("FAIL: " + "; ".join(problems))
print(f"ok: {fields} field arrays, {measures} measures as the run's own files; histories up to {longest}, "
      f"{vectors} of short vectors")

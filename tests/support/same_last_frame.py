#!/usr/bin/python3
"""Exit 0 when two H5MD trajectories end with the same step and bit for bit the same positions,
velocities and images; otherwise one FAIL line naming the array and the largest difference.
usage: same_last_frame.py A.h5 B.h5 WHAT   (WHAT: what B is, for the messages)"""
import sys

import h5py
import numpy as np

a, b = (h5py.File(p, "r") for p in sys.argv[1:3])
what = sys.argv[3]
for name in ("position", "velocity", "image"):
    sa, sb = a[f"particles/all/{name}/step"][-1], b[f"particles/all/{name}/step"][-1]
    if sa != sb:
        sys.exit(f"FAIL: {what} ends at step {sb}, the uninterrupted run at {sa}")
    x, y = a[f"particles/all/{name}/value"][-1], b[f"particles/all/{name}/value"][-1]
    if not np.array_equal(x, y):
        sys.exit(f"FAIL: {name} at the end of {what} differs from the uninterrupted run by "
                 f"{np.abs(x - y).max()}")
print(f"ok: {what} ends bit for bit as the uninterrupted run")

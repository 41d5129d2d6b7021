#!/usr/bin/python3
"""MDAnalysis's H5MD reader reads an emergent trajectory: frame count, positions, box.
usage: check_mdanalysis.py TRAJECTORY.h5
Exit 0 read correctly, 1 read wrongly, 77 MDAnalysis is not installed (ctest reports a skip)."""
import sys
import warnings

import h5py
import numpy as np


def main():
    path = sys.argv[1]
    try:
        warnings.simplefilter("ignore")
        import MDAnalysis as mda
    except ImportError:
        print("MDAnalysis not installed: skipped")
        return 77
    with h5py.File(path, "r") as f:
        x = f["particles/all/position/value"][-1]
        edges = f["particles/all/box/edges/value"][-1].diagonal()
        frames = f["particles/all/position/step"].shape[0]
    u = mda.Universe.empty(x.shape[0], trajectory=True)
    # Reduced (LJ) units have no SI conversion: read the numbers as they are.
    u.load_new(path, format="H5MD", convert_units=False)
    failures = []
    if len(u.trajectory) != frames:
        failures.append(f"MDAnalysis sees {len(u.trajectory)} frames, not {frames}")
    u.trajectory[-1]
    if not np.allclose(u.atoms.positions, x, atol=1e-4):  # MDAnalysis keeps float32
        failures.append("MDAnalysis positions differ")
    if not np.allclose(u.dimensions[:3], edges, rtol=1e-6):
        failures.append("MDAnalysis box differs")
    if failures:
        print("\n".join("FAIL: " + m for m in failures))
        return 1
    print(f"ok: MDAnalysis {mda.__version__} reads {frames} frames")
    return 0


if __name__ == "__main__":
    sys.exit(main())

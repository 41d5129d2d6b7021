#!/usr/bin/env python3
"""Copies a checkpoint and damages the copy, for the tests of refused restarts.

usage: damage_checkpoint.py SOURCE COPY STATEMENT
STATEMENT is Python run on the copy with `c` its checkpoint group, `s` its scene state (or
None), `np` numpy and `replace(name, values)` swapping a scene-state array for another.
"""
import shutil
import sys

import h5py
import numpy as np

source, copy, statement = sys.argv[1:4]
shutil.copy(source, copy)
with h5py.File(copy, "r+") as f:
    c = f["checkpoint"]
    s = c.get("scene_state")

    def replace(name, values):
        del s[name]
        s[name] = np.asarray(values, dtype=float)

    exec(statement)

#!/usr/bin/python3
"""Checks trajectory files against the H5MD 1.1 layout, and that files written on different
rank counts hold the same arrays.

usage: check_h5md.py RANKS_A FILE_A RANKS_B FILE_B
"""
import sys

import h5py
import numpy as np

ELEMENTS = {  # name: (dtype kind, itemsize, per-particle shape)
    "position": ("f", 8, (3,)),
    "velocity": ("f", 8, (3,)),
    "species": ("i", 4, ()),
    "id": ("i", 8, ()),
    "image": ("i", 4, (3,)),
}
failures = []


def expect(condition, message):
    if not condition:
        failures.append(message)


def text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def check_time_series(group, path):
    for name in ("step", "time", "value"):
        expect(name in group, f"{path}: missing {name}")
    if failures:
        return None
    step, time, value = group["step"], group["time"], group["value"]
    expect(step.dtype.kind == "i" and step.ndim == 1, f"{path}/step: not a 1-d integer array")
    expect(time.dtype.kind == "f" and time.shape == step.shape, f"{path}/time: bad shape/dtype")
    expect(value.shape[0] == step.shape[0], f"{path}/value: {value.shape[0]} frames vs {step.shape[0]} steps")
    expect(np.all(np.diff(step[:]) > 0), f"{path}/step: not increasing")
    return value


def check_file(path, ranks):
    f = h5py.File(path, "r")
    h5md = f["h5md"]
    expect(list(h5md.attrs["version"]) == [1, 1], "h5md/version != [1, 1]")
    expect("name" in h5md["author"].attrs, "h5md/author has no name")
    expect(text(h5md["creator"].attrs["name"]) == "emergent", "h5md/creator/name")
    expect("version" in h5md["creator"].attrs, "h5md/creator has no version")
    expect(h5md.attrs.get("emergent_complete") == 1, "file not marked complete")

    params = f["parameters"]
    for key in ("scene", "dt", "skin", "steps", "seed", "n_cells", "density", "output.every"):
        expect(key in params.attrs, f"parameters: missing {key}")
    expect(int(params["build"].attrs["ranks"]) == ranks, f"parameters/build/ranks != {ranks}")
    expect(len(text(params["build"].attrs["git_commit"])) > 0, "parameters/build/git_commit empty")

    box = f["particles/all/box"]
    expect(int(box.attrs["dimension"]) == 3, "box dimension != 3")
    boundary = [text(b) for b in box.attrs["boundary"]]
    expect(len(boundary) == 3 and set(boundary) <= {"periodic", "none"}, f"box boundary {boundary}")
    edges = check_time_series(box["edges"], "particles/all/box/edges")
    if edges is not None:
        expect(edges.shape[1:] == (3, 3) and edges.dtype.kind == "f", "box edges not float[frames, 3, 3]")
        expect(np.allclose(edges[:], edges[:] * np.eye(3)), "box edges not diagonal (rectangular box)")
        expect(edges.shape[0] == f["particles/all/position/step"].shape[0], "box edges: one per frame")

    n = None
    for name, (kind, size, tail) in ELEMENTS.items():
        value = check_time_series(f["particles/all/" + name], "particles/all/" + name)
        if value is None:
            continue
        n = value.shape[1] if n is None else n
        expect(value.shape[1:] == (n,) + tail, f"{name}: shape {value.shape}")
        expect(value.dtype.kind == kind and value.dtype.itemsize == size, f"{name}: dtype {value.dtype}")
    ids = f["particles/all/id/value"][:]
    expect(all(np.array_equal(frame, np.arange(n)) for frame in ids), "id frames are not 0..N-1")

    for name in ("kinetic_energy", "potential_energy", "total_energy", "temperature", "pressure", "momentum"):
        value = check_time_series(f["observables/" + name], "observables/" + name)
        if value is not None:
            expect(value.ndim == (2 if name == "momentum" else 1), f"observables/{name}: ndim {value.ndim}")
    return f


def main():
    ranks_a, path_a, ranks_b, path_b = int(sys.argv[1]), sys.argv[2], int(sys.argv[3]), sys.argv[4]
    a = check_file(path_a, ranks_a)
    b = check_file(path_b, ranks_b)
    # The first frame (step 0) comes from the same initial state on any rank count: files must
    # hold identical arrays, particle by particle, whatever the domain decomposition.
    for name in ELEMENTS:
        x = a["particles/all/" + name + "/value"][0]
        y = b["particles/all/" + name + "/value"][0]
        expect(np.array_equal(x, y), f"{name}: first frame differs between {ranks_a} and {ranks_b} ranks")
    if failures:
        print("\n".join("FAIL: " + m for m in failures))
        sys.exit(1)
    print(f"ok: H5MD layout valid; {ranks_a}- and {ranks_b}-rank files hold the same first frame")


main()

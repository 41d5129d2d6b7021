"""Reading emergent's output files (h5py, numpy): the base of the figure scripts.

    from emergentpy import Run
    run = Run("out/lj")
    t, T = run.observable("temperature")
    step, x = run.frame("position", -1)        # last frame, particles in id order
    times, rho = run.field("box", "density")   # [frames, n_s, n_y, n_x]

A continued run (its trajectory.from<STEP>.h5 and fields.from<STEP>.h5) reads as one.
"""
import glob
import os
import re

import h5py
import numpy as np


def _joined(pieces):
    """Concatenates (time, value) pieces, keeping from each only the times after the last."""
    times, values, last = [], [], -np.inf
    for t, v in pieces:
        keep = t > last + 1e-9
        times.append(t[keep])
        values.append(v[keep])
        if keep.any():
            last = t[keep][-1]
    if not times:
        raise KeyError("no segment holds it")
    return np.concatenate(times), np.concatenate(values)


def _segments(directory, stem):
    """stem.h5, then the continued runs' stem.from<STEP>.h5 in step order."""
    files = glob.glob(os.path.join(directory, stem + ".from*.h5"))
    files.sort(key=lambda f: int(re.search(r"from(\d+)\.h5$", f).group(1)))
    first = os.path.join(directory, stem + ".h5")
    return ([first] if os.path.exists(first) else []) + files


class Run:
    """One output directory: trajectory.h5 (H5MD), fields.h5, summary.json. A run continued
    from checkpoints (trajectory.from<STEP>.h5, fields.from<STEP>.h5) is read as one run:
    series and fields are joined in time; parameters, box and completeness come from the last
    segment. Naming a file (trajectory=..., fields=...) reads that segment alone."""

    def __init__(self, directory, trajectory=None, fields=None):
        self.directory = directory
        self.trajectory_paths = ([os.path.join(directory, trajectory)] if trajectory else
                                 _segments(directory, "trajectory")
                                 or [os.path.join(directory, "trajectory.h5")])
        self.fields_paths = ([os.path.join(directory, fields)] if fields else
                             _segments(directory, "fields") or [os.path.join(directory, "fields.h5")])
        self.trajectory_path = self.trajectory_paths[0]
        self.fields_path = self.fields_paths[0]

    def _trajectory(self):
        return h5py.File(self.trajectory_paths[-1], "r")

    def parameters(self):
        """Every resolved run parameter, as text (of the last segment: a continued run may
        have changed some, typically steps)."""
        with self._trajectory() as f:
            return {k: (v.decode() if isinstance(v, bytes) else v) for k, v in f["parameters"].attrs.items()}

    def complete(self):
        with self._trajectory() as f:
            return int(f["h5md"].attrs.get("emergent_complete", 0)) == 1

    def observables(self):
        names = set()
        for path in self.trajectory_paths:
            with h5py.File(path, "r") as f:
                names.update(f["observables"].keys())
        return sorted(names)

    def observable(self, name):
        """(time, value) arrays of /observables/<name>, over every segment that holds it (a
        killed segment may have kept none)."""
        pieces = []
        for path in self.trajectory_paths:
            with h5py.File(path, "r") as f:
                if name in f["observables"]:
                    g = f["observables"][name]
                    pieces.append((g["time"][:], g["value"][:]))
        return _joined(pieces)

    def frame(self, element, index=-1):
        """(step, value) of one frame of a particle element, in particle-id order; frames are
        counted over the segments (a restart's first frame repeats its checkpoint's step)."""
        counts = []
        for path in self.trajectory_paths:
            with h5py.File(path, "r") as f:
                counts.append(len(f["particles/all"][element]["step"]))
        index = index + sum(counts) if index < 0 else index
        for path, n in zip(self.trajectory_paths, counts):
            if index < n:
                with h5py.File(path, "r") as f:
                    g = f["particles/all"][element]
                    return int(g["step"][index]), g["value"][index]
            index -= n
        raise IndexError("frame index out of range")

    def box(self):
        with self._trajectory() as f:
            b = f["particles/all/box"]
            offset = b["offset"][:] if "offset" in b else np.zeros(3)
            edges = b["edges/value"][-1].diagonal() if isinstance(b["edges"], h5py.Group) else b["edges"][:]
            return offset, offset + edges

    def unwrapped_positions(self, index=-1):
        """Positions plus image counts times the box edges."""
        _, x = self.frame("position", index)
        _, image = self.frame("image", index)
        lo, hi = self.box()
        return x + image * (hi - lo)

    def field_grids(self):
        with h5py.File(self.fields_path, "r") as f:
            return sorted(f["fields"].keys())

    def field(self, grid, quantity):
        """(time, value) of a coarse-grained field over the segments; value is
        [frames, n_s, n_y|theta, n_x|r(, 3)]."""
        pieces = []
        for path in self.fields_paths:
            with h5py.File(path, "r") as f:
                g = f["fields"][grid][quantity]
                pieces.append((g["time"][:], g["value"][:]))
        return _joined(pieces)

    def field_axes(self, grid):
        """Cell-centre coordinates along the grid's three axes (x|r, y|theta, z|s)."""
        with h5py.File(self.fields_path, "r") as f:
            g = f["fields"][grid]
            n = g.attrs["shape"]
            if g.attrs["kind"] in (b"cylindrical", "cylindrical"):
                axis = int(g.attrs["axis"])
                lo = [g.attrs["r_min"], g.attrs["theta_min"], g.attrs["lo"][axis]]
                hi = [g.attrs["r_max"], g.attrs["theta_max"], g.attrs["hi"][axis]]
            else:
                lo, hi = g.attrs["lo"], g.attrs["hi"]
            return [lo[d] + (np.arange(n[d]) + 0.5) * (hi[d] - lo[d]) / n[d] for d in range(3)]

    def segments(self):
        """The trajectory files of this directory: the original and continued runs."""
        return list(self.trajectory_paths)

    def _census_body_frames(self):
        """Per segment holding bodies with bond census values: (open group particles/bodies,
        its frame names in order). The file stays open while the caller reads it."""
        for path in self.trajectory_paths:
            with h5py.File(path, "r") as f:
                if "particles/bodies" in f and "bonds" in f["particles/bodies"]:
                    g = f["particles/bodies"]
                    yield g, sorted(g["frames/cluster"].keys(), key=int)

    def body_frames(self):
        """The rigid bodies' frames that carry bond census values (capsid-assembly's `cluster`,
        `cluster_size`, `bonds`), over the run's segments, bodies ordered by id: (steps,
        cluster, size, bonds, centres, box edges), arrays indexed [frame, body]; their times are
        body_frame_times()."""
        steps, cluster, size, bonds, centres, edges = [], [], [], [], [], None
        for g, keys in self._census_body_frames():
            fr = g["frames"]
            for k in keys:
                order = np.argsort(fr["id"][k][:])
                steps.append(int(g["cluster/step"][int(k)]))
                cluster.append(fr["cluster"][k][:][order])
                size.append(fr["cluster_size"][k][:][order])
                bonds.append(fr["bonds"][k][:][order])
                centres.append(fr["position"][k][:][order])
            e = np.asarray(g["box/edges/value"][0], float)
            edges = np.diag(e) if e.ndim == 2 else e
        return (np.array(steps, int), np.array(cluster), np.array(size), np.array(bonds).astype(int),
                np.array(centres), edges)

    def census_particle_frame(self, index=-1):
        """One frame holding both the particles and the bodies' bond census (capsid-assembly):
        (step, time, particle positions, species, body cluster ids, cluster sizes, box lengths,
        bonds per body), particles and bodies each in id order. index counts those frames over the segments
        (-1: the last). Raises ValueError when there is none or index is out of range."""
        frames = []
        for path in self.trajectory_paths:
            with h5py.File(path, "r") as f:
                if "particles/bodies/frames/cluster" not in f or "position" not in f["particles/all/frames"]:
                    continue
                keys = sorted(f["particles/bodies/frames/cluster"].keys(), key=int)
                frames += [(path, k) for k in keys if k in f["particles/all/frames/position"]]
        if not frames:
            raise ValueError(f"{self.directory} holds no particle frame with body cluster ids")
        if not -len(frames) <= index < len(frames):
            raise ValueError(f"frame {index} out of range ({len(frames)} frames)")
        path, k = frames[index]
        with h5py.File(path, "r") as f:
            p, b = f["particles/all/frames"], f["particles/bodies/frames"]
            order, border = np.argsort(p["id"][k][:]), np.argsort(b["id"][k][:])
            edges = np.asarray(f["particles/all/box/edges/value"][-1], float)
            step = int(f["particles/bodies/cluster/step"][int(k)])
            time = float(f["particles/bodies/cluster/time"][int(k)])
            return (step, time, p["position"][k][:][order], p["species"][k][:][order], b["cluster"][k][:][border],
                    b["cluster_size"][k][:][border], edges.diagonal() if edges.ndim == 2 else edges,
                    b["bonds"][k][:][border].astype(int))

    def body_orientations(self):
        """The bodies' orientations (unit quaternions w, x, y, z) of the frames body_frames()
        returns, bodies ordered by id: array [frame, body, 4]."""
        out = []
        for g, keys in self._census_body_frames():
            fr = g["frames"]
            for k in keys:
                out.append(fr["orientation"][k][:][np.argsort(fr["id"][k][:])])
        return np.array(out)

    def body_frame_times(self):
        """The times of body_frames() (H5MD's, right across a change of dt)."""
        return np.array([float(g["cluster/time"][int(k)]) for g, keys in self._census_body_frames() for k in keys])


def cosine_modes(profiles, modes):
    """Amplitudes of the axial modes cos(m pi z / L) in profiles sampled at the centres of n
    equal cells (one profile per row, as radial_velocity_midgap with closed ends): the same
    normalisation as the scene's dominant mode. Returns {m: amplitude per row}."""
    profiles = np.atleast_2d(np.asarray(profiles, float))
    n = profiles.shape[1]
    j = np.arange(n)
    return {m: np.abs(profiles @ np.cos(np.pi * m * (j + 0.5) / n)) * 2 / n for m in modes}


def exponential_growth(t, amplitude, lo=0.03, hi=0.15):
    """Growth rate of an amplitude that grows out of noise and saturates: the slope of
    ln(amplitude) against t over the samples between lo and hi (well above the noise, well
    below saturation) up to its first maximum. Returns (rate, indices used), rate None when
    fewer than two samples qualify."""
    t, amplitude = np.asarray(t, float), np.asarray(amplitude, float)
    peak = int(np.argmax(amplitude))
    used = [i for i in range(peak + 1) if lo <= amplitude[i] <= hi]
    if len(used) < 2:
        return None, used
    return float(np.polyfit(t[used], np.log(amplitude[used]), 1)[0]), used


def wilson_interval(successes, trials, z=1.96):
    """A proportion successes / trials with its Wilson score interval (95 % for z = 1.96; exact
    enough for a few events): (p, low, high), or None for no trials."""
    if trials == 0:
        return None
    p = successes / trials
    centre = (p + z * z / (2 * trials)) / (1 + z * z / trials)
    half = z * np.sqrt(p * (1 - p) / trials + z * z / (4 * trials * trials)) / (1 + z * z / trials)
    return p, max(0.0, centre - half), min(1.0, centre + half)


def fit_sphere(x):
    """The sphere through points x [n, 3] in the least-squares sense, (centre, radius), minimising
    sum (|x_i - c|^2 - R^2)^2: |x|^2 = 2 c.x + (R^2 - |c|^2) is linear in c and R^2 - |c|^2."""
    a = np.hstack([2 * x, np.ones((len(x), 1))])
    s, *_ = np.linalg.lstsq(a, (x * x).sum(1), rcond=None)
    c = s[:3]
    return c, float(np.sqrt(max(s[3] + c @ c, 0.0)))


def rotation(q):
    """Rotation matrices (body frame to lab) of unit quaternions (w, x, y, z), one per row."""
    w, x, y, z = np.asarray(q, float).T
    return np.stack([np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], -1),
                     np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], -1),
                     np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], -1)], -2)

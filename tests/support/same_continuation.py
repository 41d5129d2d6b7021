#!/usr/bin/python3
"""Exit 0 when a run stopped at step SPLIT and continued from its checkpoint (into its own
directory) is bit for bit the uninterrupted run: thermo.dat byte for byte; every observable of
trajectory.h5 (the scene's own running measures included) at every step after SPLIT, and the
particle frames written after it; every coarse-grained field frame after it; and the summary's
averages, drift and scene measures. Otherwise one FAIL line per difference, naming it.
ROUND_OFF (optional, comma-separated) names the observables, and with "fields" the field frames,
that are sums the continuation regroups (a restored total plus new per-rank partials: wall
tallies, field accumulators over several ranks); those may differ by round-off, 1e-12 relative to
the series' largest value, and must be finite exactly where the uninterrupted run's are.
usage: same_continuation.py STRAIGHT_DIR CONTINUED_DIR SPLIT WHAT [ROUND_OFF]"""
import json
import os
import sys

import h5py
import numpy as np

straight, continued, split, what = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
round_off = set(sys.argv[5].split(",")) if len(sys.argv) > 5 and sys.argv[5] else set()
bad = []


def same(a, b):
    """Bitwise equality that counts NaN == NaN (an error bar of too few samples is NaN in both)."""
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape or a.dtype != b.dtype:
        return False
    if a.dtype.kind == "f":
        return np.array_equal(a.view(np.uint64 if a.itemsize == 8 else np.uint32),
                              b.view(np.uint64 if b.itemsize == 8 else np.uint32))
    return np.array_equal(a, b)


def close(a, b):
    """Equal but for round-off in regrouped sums: 1e-12 of the largest value, where a sum of
    O(100) doubles regrouped differs by O(1e-16) relative (measured: 5e-16, taylor-couette's wall
    tallies and field frames on 2 ranks); a sample lost or counted twice is off by O(1e-2) or more."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    if a.shape != b.shape or not np.array_equal(np.isfinite(a), np.isfinite(b)):
        return False
    ok = np.isfinite(a)
    return np.abs(a[ok] - b[ok]).max(initial=0) <= 1e-12 * (1 + np.abs(a[ok]).max(initial=0))


# thermo.dat: the continued run rewrites it from the whole series (checkpointed samples + new).
with open(f"{straight}/thermo.dat", "rb") as f:
    rows_a = f.read().splitlines()
with open(f"{continued}/thermo.dat", "rb") as f:
    rows_b = f.read().splitlines()
if rows_a != rows_b:
    diff = [i for i in range(min(len(rows_a), len(rows_b))) if rows_a[i] != rows_b[i]]
    first = diff[0] if diff else min(len(rows_a), len(rows_b))
    bad.append(f"thermo.dat: {len(rows_b)} rows against {len(rows_a)}, first difference at row "
               f"{first}: {rows_b[first] if first < len(rows_b) else b'(none)'!r} against "
               f"{rows_a[first] if first < len(rows_a) else b'(none)'!r}")


def series_after(group, name):
    """(steps, values) of an H5MD time series with steps after the split."""
    g = group[name]
    steps = g["step"][:]
    keep = steps > split
    return steps[keep], g["value"][:][keep]


ta = h5py.File(f"{straight}/trajectory.h5", "r")
tb = h5py.File(f"{continued}/trajectory.from{split}.h5", "r")
names_a, names_b = set(ta["observables"]), set(tb["observables"])
if names_a != names_b:
    bad.append(f"observables: the continuation has {sorted(names_b ^ names_a)} where the "
               "uninterrupted run does not, or the reverse")
if not names_a:
    bad.append("the uninterrupted run recorded no observables")
for name in sorted(round_off - names_a - {"fields"}):
    bad.append(f"{name} is allowed round-off but is no observable of the run")
for name in sorted(names_a & names_b):
    sa, va = series_after(ta["observables"], name)
    sb, vb = series_after(tb["observables"], name)
    if not np.array_equal(sa, sb):
        bad.append(f"observable {name}: sampled at {list(sb)} after step {split}, the "
                   f"uninterrupted run at {list(sa)}")
    elif len(sa) == 0:
        bad.append(f"observable {name}: no sample after step {split}")
    elif not (close(va, vb) if name in round_off else same(va, vb)):
        bad.append(f"observable {name} differs after step {split}")
frames = 0
for name in ("position", "velocity", "image", "species", "id"):
    if name not in ta["particles/all"]:
        continue
    sa, va = series_after(ta["particles/all"], name)
    sb, vb = series_after(tb["particles/all"], name)
    if not np.array_equal(sa, sb) or len(sa) == 0:
        bad.append(f"particle {name}: frames at {list(sb)} after step {split}, the uninterrupted "
                   f"run's at {list(sa)}")
    elif not same(va, vb):
        worst = np.abs(va.astype(float) - vb.astype(float)).max()
        bad.append(f"particle {name} differs after step {split} (by up to {worst:.3g})")
    frames = len(sa)

# Fields: a frame whose interval holds the split sums samples from both runs.
if os.path.exists(f"{straight}/fields.h5"):
    fa = h5py.File(f"{straight}/fields.h5", "r")
    fb = h5py.File(f"{continued}/fields.from{split}.h5", "r")
    quantities = []
    fa.visit(lambda n: quantities.append(n[:-len("/value")]) if n.endswith("/value") else None)
    if not quantities:
        bad.append("the uninterrupted run wrote no field frames")
    for q in quantities:
        if q not in fb:
            bad.append(f"field {q} missing after the restart")
            continue
        sa, va = series_after(fa, q)
        sb, vb = series_after(fb, q)
        if not np.array_equal(sa, sb) or len(sa) == 0:
            bad.append(f"field {q}: frames at {list(sb)}, the uninterrupted run's at {list(sa)}")
        elif not (close(va, vb) if "fields" in round_off else same(va, vb)):
            bad.append(f"field {q} differs after step {split}")

# The summary: what the run measured (not how long it took).
ja = json.load(open(f"{straight}/summary.json"))
jb = json.load(open(f"{continued}/summary.json"))
keys = [k for k in ja if k in ("N", "steps", "samples", "final_momentum", "scene_measures")
        or k.startswith(("mean_", "stderr_", "energy_drift"))]
for k in keys:
    if ja[k] != jb.get(k):
        bad.append(f"summary {k}: {jb.get(k)} against {ja[k]}")
if bad:
    print(f"FAIL: {what}:", *bad, sep="\n  ")
    sys.exit(1)
print(f"ok: {what}: thermo.dat ({len(rows_a) - 1} rows), {len(names_a)} observables, "
      f"{frames} particle frame(s) and the summary bit for bit after step {split}"
      + (f" ({', '.join(sorted(round_off))} within round-off)" if round_off else ""))

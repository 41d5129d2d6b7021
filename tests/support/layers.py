#!/usr/bin/python3
"""The engine's layers hold (docs/architecture.md, "Layers"): no include from a lower layer to a
higher one, scenes only through the public headers, the engine's API apart from the scene kit.

usage: layers.py SOURCE_DIR

1. Folders of the engine, lowest first (LAYERS below). A file includes its own folder's headers
   and lower ones'. A public header (include/emergent/NAME.hpp) belongs to the folder whose
   NAME.cpp implements it: including it from a lower folder is an upward include too (the
   store's header, implemented in particles/, from decomposition/ is fine; from below not).
2. The engine's API (include/emergent/*.hpp) includes no scene-kit header (include/emergent/kit/).
3. Scenes (problems/) include only public headers, and ask the engine for time and range
   (Simulation::measurement_start, steps_in, interaction_range) instead of reading the run
   parameters `dt` and `skin` (their values are the engine's to apply, and may change on a
   continuation).
Each breach is one line; exit 1 if any.
"""
import os
import re
import sys

LAYERS = ["execution", "gpu", "particles", "decomposition", "rigid", "neighbour", "force",
          "boundary", "integrate", "thermostat", "observe", "core", "kit", "io", "app"]
RANK = {name: k for k, name in enumerate(LAYERS)}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)

root = sys.argv[1]
failures = []


def sources(folder):
    base = os.path.join(root, folder)
    for dirpath, _, names in os.walk(base):
        for name in sorted(names):
            if name.endswith((".hpp", ".cpp", ".cu", ".cuh")):
                yield os.path.relpath(os.path.join(dirpath, name), root)


def folder_of(path):
    parts = path.split("/")
    return "decomposition" if parts[0] == "decomposition" else parts[1]


# Where each public header is implemented.
implemented = {}
for path in list(sources("src")) + list(sources("decomposition")):
    stem, ext = os.path.splitext(os.path.basename(path))
    if ext in (".cpp", ".cu"):
        implemented.setdefault(stem, folder_of(path))

# Public headers with no NAME.cpp of their own, and the folder they belong to.
HEADER_ONLY = {"neighbour_loop": "force", "pair_law": "force"}
for stem, folder in HEADER_ONLY.items():
    implemented.setdefault(stem, folder)

engine_files = list(sources("src")) + list(sources("decomposition"))
for path in engine_files:
    me = folder_of(path)
    if me not in RANK:
        failures.append(f"{path}: folder '{me}' is in no layer (tests/support/layers.py, docs/architecture.md)")
        continue
    for target in INCLUDE.findall(open(os.path.join(root, path)).read()):
        head = target.split("/")[0]
        if head == "emergent":
            stem = os.path.splitext(os.path.basename(target))[0]
            owner = implemented.get(stem)
            if owner in RANK and RANK[owner] > RANK[me]:
                failures.append(f"{path}: includes {target}, implemented in {owner}/, a higher layer than {me}/")
        elif head in RANK and RANK[head] > RANK[me]:
            failures.append(f"{path}: includes {target}, from {head}/, a higher layer than {me}/")

for path in sources("include/emergent"):
    if "/kit/" in path:
        continue
    for target in INCLUDE.findall(open(os.path.join(root, path)).read()):
        if target.startswith("emergent/kit/"):
            failures.append(f"{path}: the engine's API includes the scene kit's {target}")

for path in sources("problems"):
    text = open(os.path.join(root, path)).read()
    for target in INCLUDE.findall(text):
        if not target.startswith("emergent/"):
            failures.append(f"{path}: a scene includes {target}, not a public header")
    for key in ("dt", "skin"):
        if re.search(r'\.(real|text)\("%s"\)' % key, text):
            failures.append(f"{path}: a scene reads the run parameter '{key}' (ask the engine: "
                            "measurement_start, steps_in, interaction_range)")

print(f"{len(engine_files)} engine files in {len(LAYERS)} layers checked")
for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)

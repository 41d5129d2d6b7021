#!/usr/bin/python3
"""The repository stays lean: the tracked files together within 15 MiB, and every tracked file
over 1 MiB declared, with its reason, in benchmarks/logs/large_files.txt, whose files together
stay within the budget it states. A declared file that is no longer tracked is stale and fails
too. Outside a git checkout (a source archive) there is nothing to count: skipped (77).
usage: repository_budget.py SOURCE_DIR"""
import os
import subprocess
import sys

MIB = 1 << 20
TREE_LIMIT = 15 * MIB
LARGE = 1 * MIB

root = sys.argv[1]
try:
    listing = subprocess.run(["git", "-C", root, "ls-files", "-z"], check=True,
                             capture_output=True).stdout.decode()
except (OSError, subprocess.CalledProcessError):
    print("SKIPPED: not a git checkout")
    sys.exit(77)
tracked = [p for p in listing.split("\0") if p]
sizes = {p: os.path.getsize(os.path.join(root, p)) for p in tracked
         if os.path.isfile(os.path.join(root, p))}
failures = []
total = sum(sizes.values())
if total > TREE_LIMIT:
    largest = sorted(sizes.items(), key=lambda kv: -kv[1])[:5]
    failures.append(f"tracked files hold {total / MIB:.1f} MiB, over 15 MiB; largest: " +
                    ", ".join(f"{p} ({s / MIB:.2f} MiB)" for p, s in largest))
declared, budget = {}, None
with open(os.path.join(root, "benchmarks/logs/large_files.txt")) as f:
    for line in f:
        words = line.split()
        if not words or words[0].startswith("#"):
            continue
        if words[0] == "budget_mib":
            budget = float(words[1]) * MIB
        else:
            declared[words[0]] = " ".join(words[1:])
if budget is None:
    failures.append("large_files.txt states no budget_mib")
for path, why in declared.items():
    if path not in sizes:
        failures.append(f"declared {path} is not tracked (remove the line)")
    elif not why:
        failures.append(f"declared {path} without a reason")
for path, size in sizes.items():
    if size > LARGE and path not in declared:
        failures.append(f"{path} is {size / MIB:.2f} MiB, over 1 MiB and not declared in large_files.txt")
large_total = sum(sizes.get(p, 0) for p in declared)
if budget is not None and large_total > budget:
    failures.append(f"declared large files hold {large_total / MIB:.2f} MiB, over the budget "
                    f"of {budget / MIB:g} MiB")
print(f"{len(sizes)} tracked files, {total / MIB:.2f} MiB (limit 15); declared large files "
      f"{large_total / MIB:.2f} MiB (budget {budget / MIB if budget else 0:g})")
for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)

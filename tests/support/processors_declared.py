#!/usr/bin/python3
"""Every registered test that starts several processes declares at least that many PROCESSORS,
so that `ctest -j N` never runs more processes than cores (oversubscribed MPI ranks busy-wait:
two such tests side by side on 2 cores ran several times slower and hit their time limits).
Reads the tests from `ctest --show-only=json-v1` and, for each, its command line and the
scripts it names (a sourced tests/support/mpi_run.sh counts as part of the script); a test needs
  N for a literal `-np N`, the largest of `for np in A B ...` (or of the leading numbers of
    `for case in "N ..." ...`), `run N` in a script that starts ranks through mpirun, or the
    script's own argument that `-np "$var"` takes (`var=$3`: the third word after the script);
  2 when a script starts two or more background jobs (lines ending in `&`) before a `wait`.
Prints one FAIL line per test that declares fewer, and exits 1.
usage: processors_declared.py CTEST BUILD_DIR"""
import json
import os
import re
import subprocess
import sys

ctest, build = sys.argv[1], sys.argv[2]
listing = subprocess.run([ctest, "--show-only=json-v1", "--test-dir", build], check=True,
                         capture_output=True, text=True).stdout
tests = json.loads(listing)["tests"]


def script_text(path):
    text = open(path, errors="replace").read()
    if re.search(r"^\s*(\.|source)\s.*mpi_run\.sh", text, re.M):
        text += open(os.path.join(os.path.dirname(path), "..", "support", "mpi_run.sh")).read()
    return text


def needed(command):
    need, why = 1, []
    words = [str(w) for w in command]
    joined = " ".join(words)
    for m in re.finditer(r"-np\s+(\d+)", joined):
        need, why = max(need, int(m.group(1))), why + [f"-np {m.group(1)}"]
    for i, w in enumerate(words):
        if not (os.path.isfile(w) and w.endswith((".sh", ".bash"))):
            continue
        text = script_text(w)
        code = "\n".join(line for line in text.splitlines() if not line.lstrip().startswith("#"))
        name = os.path.basename(w)
        mpi = re.search(r"\bmpirun\b|\$mpirun|\bmpi\[@\]", code) is not None
        for m in re.finditer(r"-np\s+\"?(\d+)\b", code):
            need, why = max(need, int(m.group(1))), why + [f"{name}: -np {m.group(1)}"]
        for m in re.finditer(r"for np in ([\d ]+);", code):
            n = max(int(x) for x in m.group(1).split())
            need, why = max(need, n), why + [f"{name}: for np in {m.group(1).strip()}"]
        for m in re.finditer(r"for \w+ in ((?:\"\d+[^\"]*\"\s*)+);", code):
            n = max(int(x) for x in re.findall(r"\"(\d+)", m.group(1)))
            need, why = max(need, n), why + [f"{name}: for ... in {m.group(1).strip()}"]
        positional = dict(re.findall(r"^\s*(\w+)=\$\{?(\d)\b", code, re.M))
        for var in set(re.findall(r"-np\s+\"?\$\{?(\w+)", code)):
            k = positional.get(var)
            if k is not None and i + int(k) < len(words) and words[i + int(k)].isdigit():
                n = int(words[i + int(k)])
                need, why = max(need, n), why + [f"{name}: -np ${var} = {n}"]
        if mpi:
            for m in re.finditer(r"^\s*run (\d+) ", code, re.M):
                need, why = max(need, int(m.group(1))), why + [f"{name}: run {m.group(1)}"]
        background = 0
        for line in code.splitlines():
            if re.search(r"(?<!&)&\s*$", line):
                background += 1
                if background >= 2:
                    need, why = max(need, 2), why + [f"{name}: two background jobs at once"]
            elif re.search(r"\bwait\b", line):
                background = 0
    return need, why


bad = []
for t in tests:
    props = {p["name"]: p["value"] for p in t.get("properties", [])}
    declared = int(props.get("PROCESSORS", 1))
    need, why = needed(t.get("command", []))
    if declared < need:
        bad.append(f"{t['name']}: PROCESSORS {declared}, needs {need} ({'; '.join(sorted(set(why)))})")
if not tests:
    bad.append(f"no tests listed in {build}")
if bad:
    print("FAIL: tests that start more processes than they declare:", *bad, sep="\n  ")
    sys.exit(1)
print(f"ok: {len(tests)} tests declare the processes they start")

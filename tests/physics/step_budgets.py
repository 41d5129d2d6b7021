#!/usr/bin/env python3
"""The step ledger holds its budgets: every scene's `tiny` run on the `checking` back end (which
launches, reads back and copies what a device run would) on 1 and 2 ranks, and the WCA fluid
without a thermostat (the speed benchmark's physics), report in summary.json the most passes,
read-backs, collectives and arrays moved that one plain step, one sampled step and one list
build took (Simulation::step_ledger). None may exceed its budget below: the counts are exact
(no timing in them), so a change that adds a pass, a read-back, a collective or a copy fails
here and must either be undone or move its budget in a commit that says why.

The WCA budgets are the device's targets: a plain step 4 passes (kick-drift with the rebuild
test, ghost refresh, forces, kick), 1 read-back (the rebuild test's displacement), 1 collective
(the rebuild vote), no array; a list build on one rank 12 passes and 2 read-backs (one pass
bringing particles home and keying them, one sort, one gather; every kind of periodic image
counted, scanned and written in three passes; the list's cells keyed, sorted and started, its
rows counted, scanned and filled; back come the images' counts with the migration's faults, and
the list's length). Every scene without a wedge or bodies builds so on one rank. With its Bussi
thermostat the fluid's plain step takes 1 read-back and 1 collective too: the thermostat acts at
the step's start, its kinetic energy summed in the kick-drift's pass and carried by the rebuild
vote, and one pass applies its factor as if before the drift (5 passes). Where walls, bodies or
wall layers are present the thermostat or the layers keep their own sum at the step's end
(capsid-assembly, rayleigh-benard: 2 collectives). The other rows are what each scene takes
today (2026-12-07, benchmarks/logs/step_ledger_2026-12-07_reads_only.log; the thermostatted
fluid's since the vote carries the thermostat, benchmarks/logs/step_ledger_2026-12-07_one_vote.log;
the general path's list builds, 6 to 10 passes fewer since a ghost's fields, image and turned
velocity are copied in one pass, benchmarks/logs/step_ledger_2026-12-08_ghost_copies.log), not
targets. On one rank no plain step moves an array but vibrated-sawtooth's: after its
on_equilibrated removes the layer's drift (host code writing through particles()), the fields
that marked changed go back once, two of them in a plain step.

usage: step_budgets.py EMERGENT MPIRUN"""
import json
import os
import subprocess
import sys
import tempfile

# (scene, ranks, extra settings): {kind: (passes, read_backs, collectives, arrays)}
BUDGETS = {
    ("lj-fluid", 1, "thermostat=none"): {"plain_step": (4, 1, 1, 0), "sampled_step": (6, 3, 1, 0),
                                         "list_build": (12, 2, 1, 0)},
    ("lj-fluid", 2, "thermostat=none"): {"plain_step": (9, 1, 1, 4), "sampled_step": (11, 3, 1, 4),
                                         "list_build": (54, 16, 3, 7)},
    ("lj-fluid", 1, ""): {"plain_step": (5, 1, 1, 0), "sampled_step": (7, 3, 1, 0), "list_build": (12, 2, 1, 0)},
    ("lj-fluid", 2, ""): {"plain_step": (10, 1, 1, 4), "sampled_step": (12, 3, 1, 4), "list_build": (54, 16, 3, 7)},
    ("capsid-assembly", 1, ""): {"plain_step": (11, 2, 2, 0), "sampled_step": (13, 4, 2, 0),
                                 "list_build": (31, 8, 4, 1)},
    ("capsid-assembly", 2, ""): {"plain_step": (16, 2, 2, 4), "sampled_step": (18, 4, 2, 4),
                                 "list_build": (83, 26, 4, 9)},
    ("granular-bed", 1, ""): {"plain_step": (8, 1, 1, 0), "sampled_step": (14, 7, 1, 0), "list_build": (12, 2, 1, 0)},
    ("granular-bed", 2, ""): {"plain_step": (18, 1, 1, 8), "sampled_step": (24, 7, 1, 8), "list_build": (52, 14, 3, 4)},
    ("planar-couette", 1, ""): {"plain_step": (7, 3, 1, 0), "sampled_step": (9, 5, 1, 0),
                                "list_build": (12, 2, 2, 0)},
    ("planar-couette", 2, ""): {"plain_step": (12, 3, 1, 2), "sampled_step": (14, 5, 1, 2),
                                "list_build": (53, 15, 4, 4)},
    ("rayleigh-benard", 1, ""): {"plain_step": (13, 5, 2, 0), "sampled_step": (15, 8, 2, 0),
                                 "list_build": (12, 2, 2, 0)},
    ("rayleigh-benard", 2, ""): {"plain_step": (17, 5, 2, 4), "sampled_step": (20, 8, 2, 4),
                                 "list_build": (54, 16, 4, 8)},
    ("rotating-drum", 1, ""): {"plain_step": (24, 1, 1, 0), "sampled_step": (24, 11, 1, 0),
                               "list_build": (30, 7, 4, 0)},
    ("rotating-drum", 2, ""): {"plain_step": (24, 1, 1, 4), "sampled_step": (34, 11, 1, 4),
                               "list_build": (80, 23, 4, 3)},
    ("taylor-couette", 1, ""): {"plain_step": (16, 5, 1, 0), "sampled_step": (18, 7, 1, 0),
                                "list_build": (46, 11, 4, 0)},
    ("taylor-couette", 2, ""): {"plain_step": (16, 5, 1, 2), "sampled_step": (18, 7, 1, 2),
                                "list_build": (62, 17, 4, 4)},
    ("vibrated-sawtooth", 1, ""): {"plain_step": (15, 4, 1, 2), "sampled_step": (27, 16, 1, 0),
                                   "list_build": (12, 2, 2, 0)},
    ("vibrated-sawtooth", 2, ""): {"plain_step": (25, 4, 1, 8), "sampled_step": (37, 16, 1, 8),
                                   "list_build": (54, 16, 4, 8)},
}
FIELDS = ("passes", "read_backs", "collectives", "arrays")


def main():
    exe, mpirun = sys.argv[1], sys.argv[2]
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    listed = subprocess.run([exe, "list"], capture_output=True, text=True, check=True).stdout.split()
    scenes = {line for line in listed if "-" in line and line in {k[0] for k in BUDGETS}}
    missing = {k[0] for k in BUDGETS} - scenes
    failures = []
    if missing:
        failures.append(f"scenes with a budget that `emergent list` does not name: {sorted(missing)}")
    with tempfile.TemporaryDirectory() as tmp:
        for (scene, ranks, extra), budget in BUDGETS.items():
            out = os.path.join(tmp, f"{scene}.{ranks}.{len(extra)}")
            sets = ["--set", "backend=checking", "--set", "progress_interval=0"]
            if extra:
                sets += ["--set", extra]
            cmd = [mpirun, "-q", "--oversubscribe", "-np", str(ranks), exe, "run", scene, "--preset", "tiny",
                   *sets, "-o", out, "--summary-json", out + ".json"]
            run = subprocess.run(cmd, capture_output=True, text=True, env=env)
            if run.returncode != 0:
                failures.append(f"{scene} on {ranks}: exit {run.returncode}: {run.stdout[-300:]}{run.stderr[-300:]}")
                continue
            ledger = json.load(open(out + ".json"))["step_ledger"]
            for kind in ("plain_steps", "sampled_steps", "builds"):
                if ledger[kind] < 1:  # a kind never seen would hold any budget
                    failures.append(f"{scene} on {ranks} {extra}: no {kind} in the run")
            for kind, limits in budget.items():
                got = tuple(ledger[kind][f] for f in FIELDS)
                over = [f"{f} {g} > {b}" for f, g, b in zip(FIELDS, got, limits) if g > b]
                print(f"{scene:18} np{ranks} {extra:16} {kind:13} {got} budget {limits}")
                if over:
                    failures.append(f"{scene} on {ranks} rank(s) {extra}: {kind}: " + ", ".join(over))
    for f in failures:
        print("FAIL:", f)
    print(f"step_budgets: {len(BUDGETS)} runs, {len(failures)} over budget or failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

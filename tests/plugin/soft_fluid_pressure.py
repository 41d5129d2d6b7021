#!/usr/bin/env python3
"""An out-of-tree pair law, run and checked: the soft-fluid plugin (soft_fluid.cpp) defines the
soft repulsion of dissipative particle dynamics in its own evaluator, from the public headers
alone. Its fluid at a = 25, density 3, k_B T = 1 must have the pressure published for it:
P = 23.637(2) (Lowe thermostat) and 23.635(2) (Shardlow), Allen & Tildesley, Computer
Simulation of Liquids, 2nd ed., examples, program dpd (wiki page "Fortran Simulation DPD").
Checked on the host back end (half list), the checking back end (the full list, the device's
loops) and on 2 ranks (ghosts and halo), each a separate run of 648 particles, 10000 steps.

Tolerance: 4 standard errors of the difference (the run's block-averaged error, ~0.008, and the
reference's 0.002) plus 0.02 (0.1 %) for what differs between the two sides and is not noise:
the time step (here dt 0.01 gave 23.647(8), dt 0.005 23.637(9): at most ~0.02 between them)
and the system size (the reference's is smaller). A wrong law fails by far more: a force off by
1 % moves the excess pressure (20.6) by 0.2. The energy is not compared with a reference here
(only that it is far from zero); the same law at r_c = 1 (SoftSphere, eps = a) has its energy
checked against its force by tests/unit/test_new_pair_law.cpp.
usage: soft_fluid_pressure.py EMERGENT PLUGIN MPIRUN"""
import json, math, os, subprocess, sys, tempfile

exe, plugin, mpirun = sys.argv[1:4]
REFERENCE, REFERENCE_ERROR = 23.636, 0.002
failures = 0
with tempfile.TemporaryDirectory() as work:
    for name, ranks, backend in (("host", 1, "host"), ("checking", 1, "checking"), ("host, 2 ranks", 2, "host")):
        tag = name.replace(" ", "_").replace(",", "")
        out, summary = os.path.join(work, tag), os.path.join(work, tag + ".json")
        cmd = [exe, "--plugin", plugin, "run", "soft-fluid", "--preset", "check", "--set", "backend=" + backend,
               "-o", out, "--summary-json", summary]
        if ranks > 1:
            cmd = [mpirun, "-q", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks)] + cmd
        run = subprocess.run(cmd, capture_output=True, text=True)
        if run.returncode != 0:
            print(f"FAIL {name}: exit {run.returncode}\n{run.stdout}{run.stderr}")
            failures += 1
            continue
        s = json.load(open(summary))
        p, err = s["mean_pressure"], s["stderr_pressure"]
        tol = 4 * math.hypot(err, REFERENCE_ERROR) + 0.02
        # The law acts: its energy per particle at this state is far from zero (the ideal gas's
        # pressure would be 3), and the thermostat holds T = 1 (block error ~0.002; 1 %).
        u = s["mean_potential_energy"]
        ok = abs(p - REFERENCE) <= tol and abs(s["mean_temperature"] - 1) < 0.01 and u > 1 and s["N"] == 648
        print(f"{'ok  ' if ok else 'FAIL'} {name}: P = {p:.4f} +- {err:.4f} against {REFERENCE} "
              f"(tolerance {tol:.4f}); T = {s['mean_temperature']:.4f}; U/N = {u:.4f}")
        failures += not ok
sys.exit(1 if failures else 0)

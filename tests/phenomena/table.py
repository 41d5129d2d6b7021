#!/usr/bin/python3
"""scripts/phenomena_table: its binomial interval against published values, and its table of
the committed logs (every logged run has a verdict, the taylor-couette fraction is printed).
usage: table.py SCRIPTS_DIR LOG_DIR"""
import contextlib
import importlib.machinery
import io
import sys

sys.path.insert(0, sys.argv[1])  # the script's own modules (emergentpy), as when it runs itself
table = importlib.machinery.SourceFileLoader("phenomena_table", sys.argv[1] + "/phenomena_table").load_module()
failures = []
# Clopper-Pearson 95 % limits: 3 of 10 -> 0.0667-0.6525 (R's binom.test(3, 10)); 0 of 1 and
# 1 of 1 in closed form: upper 0.975, lower 0.025. Bisection converges far below the 1e-3 asked.
for k, n, expected in ((3, 10, (0.0667, 0.6525)), (0, 1, (0.0, 0.975)), (1, 1, (0.025, 1.0))):
    got = table.clopper_pearson(k, n)
    if any(abs(g - e) > 1e-3 for g, e in zip(got, expected)):
        failures.append(f"interval {k} of {n}: {got}, expected {expected}")
out = io.StringIO()
sys.argv = ["phenomena_table", sys.argv[2]]
with contextlib.redirect_stdout(out):
    code = table.main()
text = out.getvalue()
rows = [line for line in text.splitlines() if line.startswith("| ")]
if code != 0:
    failures.append(f"exit {code} on the committed logs")
if not rows or not all(("| PASS: " in r) or ("| FAIL: " in r) for r in rows):
    failures.append(f"rows without a verdict:\n{text}")
if "taylor-couette: 4 vortices in" not in text:
    failures.append("no taylor-couette fraction")
if "capsid-assembly from monomers: a closed shell that held in" not in text:
    failures.append("no capsid-assembly fraction of seeds that closed a shell")
if "rayleigh-benard: " not in text or "seed 12345: Nu 1.048" not in text:
    failures.append("no rayleigh-benard Nusselt numbers (the logged 1000-tau run: 1.048)")
for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)

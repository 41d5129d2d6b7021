#!/usr/bin/python3
"""scripts/check_phenomenon's rayleigh-benard verdict on made-up series: convection that has
levelled off (Nu 1.10 with noise, 4 cells) passes; the same mean still climbing through the
last quarter (a rise of 0.08 across it) fails, as do Nu below 1.05 and too few cells.
usage: rayleigh_benard_check.py SCRIPTS_DIR"""
import contextlib
import importlib.machinery
import io
import sys

sys.path.insert(0, sys.argv[1])
check = importlib.machinery.SourceFileLoader("check_phenomenon", sys.argv[1] + "/check_phenomenon").load_module()


class Series:
    """What the check reads of a run: (times, values) per observable."""

    def __init__(self, nu, cells):
        self.data = {"nusselt": nu, "cell_count": cells}

    def observable(self, name):
        values = self.data[name]
        return [25.0 * k for k in range(len(values))], values


def verdict(nu, cells):
    with contextlib.redirect_stdout(io.StringIO()):
        return check.rayleigh_benard(Series(nu, cells), {})[0]


n = 40
wiggle = [0.004 * ((-1) ** k) for k in range(n)]
levelled = [1.10 + w for w in wiggle]
rising = [1.02 + 0.08 * k / (n - 1) if k < 30 else 1.06 + 0.08 * (k - 30) / 9 for k in range(n)]
cases = [("levelled off, 4 cells", levelled, [4] * n, True),
         ("still rising", rising, [4] * n, False),
         ("conduction", [1.0 + w for w in wiggle], [4] * n, False),
         ("two cells", levelled, [2] * n, False)]
failures = [name for name, nu, cells, want in cases if verdict(nu, cells) != want]
tail = rising[-(n // 4):]
assert sum(tail) / len(tail) >= 1.05, "the rising case must pass the mean, so that the rise decides it"
for name in failures:
    print("FAIL:", name)
print(f"rayleigh_benard_check: {len(cases)} cases, {len(failures)} wrong")
sys.exit(1 if failures else 0)

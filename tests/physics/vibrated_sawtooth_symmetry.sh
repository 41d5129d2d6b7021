#!/usr/bin/env bash
# The vibrated sawtooth's symmetries (scene vibrated-sawtooth, tiny preset: a monodisperse layer
# 4 grains deep in a periodic slot of two teeth, 6 wide), each run 300 cycles with its own seed
# (not the preset's):
#   mirrored teeth (built reflected in space) drive the opposite net flux: |F_s + F_m| < 3
#   combined standard errors;
#   symmetric teeth (gentle_fraction 0.5) and a flat base drive none: |F| < 3 standard errors;
#   the sawtooth drives one: |F| > 5 standard errors.
# Standard errors come from blocks of 16 cycles (CycleAverage: at least 16 blocks), longer than
# the flux's correlation time there (the cycle means decorrelate within about 2 cycles: a 2000-
# cycle run's blocking plateau starts at 4-cycle blocks; benchmarks/results/vibrated_sawtooth.md).
# usage: vibrated_sawtooth_symmetry.sh EMERGENT
set -euo pipefail
exe=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
run() {  # NAME SEED SETTINGS...
  local name=$1 seed=$2
  shift 2
  "$exe" run vibrated-sawtooth --preset tiny --set big_fraction=0 --set steps=150000 \
    --set progress_interval=0 --set seed="$seed" "$@" -o "$dir/$name" >/dev/null
}
run sawtooth 7101 --set base=sawtooth &
run mirrored 7202 --set base=mirrored &
wait %1 && wait %2
run symmetric 7303 --set base=sawtooth --set gentle_fraction=0.5 &
run flat 7404 --set base=flat &
wait %1 && wait %2
/usr/bin/python3 - "$dir" <<'PY'
import json, math, sys
d = sys.argv[1]
flux = {}
for name in ("sawtooth", "mirrored", "symmetric", "flat"):
    m = json.load(open(f"{d}/{name}/summary.json"))["scene_measures"]
    f, e = m["horizontal_flux"], m["horizontal_flux_stderr"]
    cycles, block = m["horizontal_flux_cycles"]
    print(f"{name:10s} flux {f:+.5f} +- {e:.5f} ({f / e:+.1f} sd; {cycles:.0f} cycles, blocks of {block:.0f})")
    if not (math.isfinite(f) and math.isfinite(e) and e > 0):
        sys.exit(f"{name}: no flux measured")
    flux[name] = (f, e)
bad = []
(fs, es), (fm, em) = flux["sawtooth"], flux["mirrored"]
combined = math.hypot(es, em)
print(f"sawtooth + mirrored = {fs + fm:+.5f} ({(fs + fm) / combined:+.1f} combined sd)")
if abs(fs + fm) >= 3 * combined:
    bad.append("mirrored teeth do not reverse the flux")
for name in ("symmetric", "flat"):
    f, e = flux[name]
    if abs(f) >= 3 * e:
        bad.append(f"{name}: a net flux of {f / e:+.1f} sd where none is driven")
if abs(fs) <= 5 * es:
    bad.append(f"sawtooth: flux only {fs / es:+.1f} sd")
if bad:
    sys.exit("FAIL: " + "; ".join(bad))
print("symmetries hold")
PY

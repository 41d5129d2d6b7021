#!/usr/bin/env bash
# The vibrated sawtooth's other containers and its start of the measured phase:
#   a small round container (ring teeth, the smooth cylinder wall backed by a hard one, the
#   lid) runs its grains through landing and 20 cycles without losing one (the engine stops a
#   run whose grain leaves the box);
#   in a periodic slot the drift the layer picked up while landing is removed as the measured
#   phase begins: the total momentum along x in the sample at that step is zero to round-off
#   (|p_x| below 1e-9 of the grains' summed |m v|, which thermo.dat's px is compared with
#   through the kinetic energy), while the layer did slide before (removed_drift != 0).
# usage: vibrated_sawtooth_runs.sh EMERGENT
set -euo pipefail
exe=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$exe" run vibrated-sawtooth --set container=cylinder --set diameter=30 --set depth=2 \
  --set equilibration_steps=2000 --set steps=10000 --set sample_every=1000 \
  --set progress_interval=0 -o "$dir/cylinder" >/dev/null
"$exe" run vibrated-sawtooth --preset tiny --set equilibration_steps=2500 --set steps=500 \
  --set sample_every=500 --set progress_interval=0 -o "$dir/slot" >/dev/null
/usr/bin/python3 - "$dir" <<'PY'
import json, math, sys
d = sys.argv[1]
def one(v):  # a one-value measure is written as a number
    return v[0] if isinstance(v, list) else v
c = json.load(open(f"{d}/cylinder/summary.json"))
print(f"cylinder: {c['N']} grains, {one(c['scene_measures']['cycles']):.0f} cycles, none lost")
s = json.load(open(f"{d}/slot/summary.json"))
drift = one(s["scene_measures"]["removed_drift"])
rows = {int(l.split()[0]): l.split() for l in open(f"{d}/slot/thermo.dat") if not l.startswith("#")}
# thermo.dat: step time temperature pressure kinetic potential total px py pz (kinetic per grain)
row = rows[2500]
n, kinetic, px = s["N"], float(row[4]), float(row[7])
scale = n * math.sqrt(2 * kinetic)  # ~ sum of |m v| for grains of unit mass
print(f"slot: removed drift {drift:+.5f}; p_x at the measured phase's start {px:+.3e} (scale {scale:.1f})")
if drift == 0:
    sys.exit("FAIL: no drift was removed (the hook did not run?)")
if abs(px) > 1e-9 * scale:
    sys.exit("FAIL: the layer still slides as the measured phase begins")
print("ok")
PY

#!/usr/bin/env bash
# vibrated-sawtooth flux map: the net horizontal flux and the velocity profiles v(z) per species
# of the paper's mixture (big fraction 0.3) in a periodic slot of two teeth (27 x 6), one factor
# at a time around a base point: Gamma 1.26 (amplitude 1 at f 0.4, g 5), gentle_fraction 1
# (vertical steep edge), depth 6 small-grain diameters. Factors: Gamma in {1.0, 1.1, 1.26, 1.5,
# 2.0} (by amplitude), gentle_fraction in {0.5, 0.7, 0.85, 1.0}, depth in {3, 6, 12}. Each run:
# 10 cycles of settling, then CYCLES measured cycles; the flux's error is from blocks of whole
# cycles (CycleAverage). Positive flux: toward +x, the direction in which the gentle edges rise.
# usage: [FLUX_MAP_SET="key=value ..."] benchmarks/sawtooth_flux_map.sh [CYCLES] [RANKS] [OUT]
#        (FLUX_MAP_SET: more settings for every run, after the map's own, e.g.
#        "base_backing=smooth big_fraction=0" for a monodisperse layer; defaults 300, 2,
#        benchmarks/logs/sawtooth_flux_map): OUT gets one summary per run (RUN.json); the table
#        goes to stdout (save it as the log); scripts/plot_sawtooth_flux_map OUT draws the figure.
set -euo pipefail
cd "$(dirname "$0")/.."
cycles=${1:-300}
ranks=${2:-2}
out=${3:-benchmarks/logs/sawtooth_flux_map}
case $cycles in ''|*[!0-9]*|0) echo "sawtooth_flux_map.sh: CYCLES='$cycles' must be a positive integer" >&2; exit 2 ;; esac
case $ranks in ''|*[!0-9]*|0) echo "sawtooth_flux_map.sh: RANKS='$ranks' must be a positive integer" >&2; exit 2 ;; esac
. benchmarks/common.sh
mkdir -p "$out"
# Amplitude for a given Gamma = (2 pi f)^2 a / g at f = 0.4, g = 5.
amplitude() { awk -v G="$1" 'BEGIN { printf "%.6f", G * 5 / (2 * 3.141592653589793 * 0.4)^2 }'; }
extra=()
for kv in ${FLUX_MAP_SET:-}; do extra+=(--set "$kv"); done
runs=()
for G in 1.0 1.1 1.26 1.5 2.0; do runs+=("gamma_$G:amplitude=$(amplitude "$G")"); done
for g in 0.5 0.7 0.85; do runs+=("gentle_$g:gentle_fraction=$g"); done
for d in 3 12; do runs+=("depth_$d:depth=$d"); done
echo "# sawtooth_flux_map.sh $cycles cycles, $ranks ranks; $(run_stamp)"
echo "# every run also: ${FLUX_MAP_SET:-(nothing)}"
commit_line
for r in "${runs[@]}"; do
  name=${r%%:*} setting=${r#*:}
  [ -f "$out/$name.json" ] && continue  # a stopped map continues where it was
  start=$(date +%s)
  # A run the engine stops (a guard, a grain leaving the box) is a result too: its message
  # goes into the table.
  if ! mpirun -q --oversubscribe -np "$ranks" "$exe" run vibrated-sawtooth --preset tiny \
      --set big_fraction=0.3 --set depth=6 --set profile_height=24 --set profile_bins=24 \
      --set sample_every=50 --set steps=$((cycles * 500)) --set progress_interval=0 \
      --set "$setting" "${extra[@]}" --summary-json "$out/$name.json" \
      >/dev/null 2>"$work/err"; then
    /usr/bin/python3 -c 'import json, sys; json.dump({"stopped": sys.argv[1]}, open(sys.argv[2], "w"))' \
      "$(tail -n 1 "$work/err")" "$out/$name.json"
  fi
  echo "# $name ($setting): $(( $(date +%s) - start )) s"
done
/usr/bin/python3 - "$out" "${runs[@]}" <<'PY'
import json, sys
out, runs = sys.argv[1], sys.argv[2:]
print("| run | setting | Gamma | N | net flux | +- | small grains | big grains | v(z) sign changes |")
print("|---|---|---|---|---|---|---|---|---|")
for r in runs:
    name, setting = r.split(":", 1)
    s = json.load(open(f"{out}/{name}.json"))
    if "stopped" in s:
        print(f"| {name} | {setting} | | | stopped: {s['stopped']} | | | | |")
        continue
    m = s["scene_measures"]
    f, e = m["horizontal_flux"], m["horizontal_flux_stderr"]
    fs, fb = m["horizontal_flux_small"], m["horizontal_flux_big"]
    species = lambda p: "-" if p[0] is None else f"{p[0]:+.4f} +- {p[1]:.4f}" if p[1] is not None else f"{p[0]:+.4f}"
    # The mixture's v(z), where both profiles have samples: count its reversals with height.
    vs, vb = m["velocity_profile_small"], m["velocity_profile_big"]
    v = [a for a in vs if a is not None]
    signs = [x > 0 for x in v if abs(x) > 0.01]
    changes = sum(1 for a, b in zip(signs, signs[1:]) if a != b)
    print(f"| {name} | {setting} | {m['gamma']:.2f} | {s['N']} | {f:+.4f} | {e:.4f} | "
          f"{species(fs)} | {species(fb)} | {changes} |")
PY

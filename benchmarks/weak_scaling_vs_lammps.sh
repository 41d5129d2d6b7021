#!/usr/bin/env bash
# Weak scaling from 1 to 2 ranks of the WCA fluid (rho = 0.8, T = 1, dt = 0.005, NVE, skin 0.3)
# through emergent and LAMMPS (plain and `-sf opt`), side by side:
# - one rank holds N1 = 4 nc1^3 atoms, two ranks N2 = 4 nc2^3 (defaults 20 and 25: 32000 atoms,
#   then 31250 per rank; fcc boxes are cubes, so the load per rank differs by 2 %, the same for
#   every program);
# - a program's efficiency in a round: its rate on two ranks over twice its rate on one, rates
#   in atom-steps per second (so the 2 % is counted per atom);
# - each round runs every program at both sizes; the order of the six runs rotates from round to
#   round, so each program and each size runs first equally often;
# - per round, emergent's efficiency over the better LAMMPS variant's; the table gives the median
#   of these per-round ratios with their min-max, beside each program's median efficiency and
#   rates, and peak resident memory (summed over ranks) per atom;
# - the raw log (machine, builds, every run) goes to LOG.
#
# usage: benchmarks/weak_scaling_vs_lammps.sh [ROUNDS] [NC1] [NC2] [LOG]
#   defaults: 5 20 25 benchmarks/logs/weak_scaling_vs_lammps_<date>.log
# Needs build/bin/emergent (or EMERGENT_EXE) and LAMMPS (`lmp`, Debian package lammps). The
# machine should be otherwise idle: two ranks on two cores share nothing else.
set -euo pipefail
cd "$(dirname "$0")/.."
rounds=${1:-5}
nc1=${2:-20}
nc2=${3:-25}
log=${4:-benchmarks/logs/weak_scaling_vs_lammps_$(date -u +%Y-%m-%d).log}
source benchmarks/common.sh
lmp_input=$PWD/benchmarks/in.wca_bench.lmp
source benchmarks/wca_programs.sh
command -v lmp >/dev/null || { echo "weak_scaling_vs_lammps.sh: needs LAMMPS (apt-get install lammps)" >&2; exit 2; }
export OMP_NUM_THREADS=1
mkdir -p "$(dirname "$log")"
{
  echo "# weak_scaling_vs_lammps.sh $rounds $nc1 $nc2"
  build_header
  echo "# each line: round program ranks N atom-steps/s peak-RSS-bytes(summed over ranks)"
} >"$log"

programs=(emergent lammps lammps-opt)
runs=()
for p in "${programs[@]}"; do runs+=("$p:1:$nc1" "$p:2:$nc2"); done
for p in "${programs[@]}"; do : >"$work/eff.$p"; : >"$work/r1.$p"; : >"$work/r2.$p"; : >"$work/mem.$p"; done
: >"$work/ratios"
for r in $(seq "$rounds"); do
  declare -A rate=()
  for k in $(seq 0 $(( ${#runs[@]} - 1 ))); do
    IFS=: read -r p np nc <<<"${runs[$(( (r + k) % ${#runs[@]} ))]}"
    read -r rt bytes < <(run_program "$p" "$np" "$nc")
    n=$((4 * nc * nc * nc))
    echo "$r $p $np $n $rt $bytes" >>"$log"
    rate[$p.$np]=$rt
    echo "$rt" >>"$work/r$np.$p"
    [ "$np" = 2 ] && echo "$bytes $n" | awk '{print $1/$2}' >>"$work/mem.$p"
  done
  for p in "${programs[@]}"; do
    echo "${rate[$p.2]} ${rate[$p.1]}" | awk '{print $1 / (2 * $2)}' >>"$work/eff.$p"
  done
  paste -d' ' <(tail -n 1 "$work/eff.emergent") <(tail -n 1 "$work/eff.lammps") <(tail -n 1 "$work/eff.lammps-opt") \
    | awk '{f = ($2 > $3 ? $2 : $3); print $1 / f}' >>"$work/ratios"
done
{
  printf '| program | 1 rank, %d atoms: atom-steps/s | 2 ranks, %d atoms: atom-steps/s | B/atom (2 ranks) | efficiency: median (min-max) |\n' \
    $((4 * nc1 * nc1 * nc1)) $((4 * nc2 * nc2 * nc2))
  printf '|---|---|---|---|---|\n'
  for p in "${programs[@]}"; do
    printf '| %s | %.3g | %.3g | %.0f | %.3f (%s) |\n' "$p" "$(median <"$work/r1.$p")" "$(median <"$work/r2.$p")" \
      "$(median <"$work/mem.$p")" "$(median <"$work/eff.$p")" "$(min_max "$work/eff.$p" 3)"
  done
  printf '\nemergent efficiency / better LAMMPS efficiency, per round: median %.3f (%s) of %d rounds\n' \
    "$(median <"$work/ratios")" "$(min_max "$work/ratios" 3)" "$rounds"
} | tee "$work/table"
{ echo "# table"; cat "$work/table"; } >>"$log"
echo "log: $log"

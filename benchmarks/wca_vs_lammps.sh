#!/usr/bin/env bash
# WCA fluid (rho = 0.8, T = 1, dt = 0.005, NVE, skin 0.3, fcc start) through emergent and
# LAMMPS (plain and `-sf opt`), side by side, as a sceptic would have it:
# - each round runs all three programs once; the order rotates from round to round, so each
#   program runs first equally often;
# - per round, emergent's rate over the faster LAMMPS variant of that round; the table gives the
#   median of these per-round ratios with their min-max, beside the medians of the rates;
# - peak resident memory of every rank (GNU time inside mpirun), summed, per particle;
# - timed loop only, after 200 warm-up steps, for both (LAMMPS: "Loop time" of its second run);
# - the raw log (machine, both builds, every run) goes to LOG (benchmarks/logs/...).
#
# usage: benchmarks/wca_vs_lammps.sh [ROUNDS] [SIZES] [RANKS] [LOG]
#   defaults: 5 "20 40" "1 2" benchmarks/logs/wca_vs_lammps_<date>.log
#   (n_cells 20 -> N = 32000; 40 -> 256000; 80 -> 2048000)
# Needs build/bin/emergent and LAMMPS (`lmp`, Debian package lammps).
set -euo pipefail
cd "$(dirname "$0")/.."
rounds=${1:-5}
sizes=${2:-"20 40"}
ranks_list=${3:-"1 2"}
log=${4:-benchmarks/logs/wca_vs_lammps_$(date -u +%Y-%m-%d).log}
source benchmarks/common.sh
lmp_input=$PWD/benchmarks/in.wca_bench.lmp
command -v lmp >/dev/null || { echo "wca_vs_lammps.sh: needs LAMMPS (apt-get install lammps)" >&2; exit 2; }
export OMP_NUM_THREADS=1
mkdir -p "$(dirname "$log")"

source benchmarks/wca_programs.sh

{
  echo "# wca_vs_lammps.sh $rounds \"$sizes\" \"$ranks_list\""
  build_header
  echo "# each line: N ranks round program atom-steps/s peak-RSS-bytes(summed over ranks)"
} >"$log"

printf '| N | ranks | emergent atom-steps/s | B/atom | LAMMPS atom-steps/s | B/atom | LAMMPS -sf opt | B/atom | emergent / faster LAMMPS: median (min-max) of %d rounds |\n' "$rounds"
printf '|---|---|---|---|---|---|---|---|---|\n'
programs=(emergent lammps lammps-opt)
for nc in $sizes; do
  n=$((4 * nc * nc * nc))
  for np in $ranks_list; do
    : >"$work/ratios"
    for p in "${programs[@]}"; do : >"$work/rate.$p"; : >"$work/mem.$p"; done
    for r in $(seq "$rounds"); do
      declare -A rate=()
      for k in 0 1 2; do
        p=${programs[$(( (r + k) % 3 ))]}
        read -r rt bytes < <(run_program "$p" "$np" "$nc")
        echo "$n $np $r $p $rt $bytes" >>"$log"
        rate[$p]=$rt
        echo "$rt" >>"$work/rate.$p"
        echo "$bytes $n" | awk '{print $1/$2}' >>"$work/mem.$p"
      done
      echo "${rate[emergent]} ${rate[lammps]} ${rate[lammps-opt]}" \
        | awk '{f = ($2 > $3 ? $2 : $3); print $1 / f}' >>"$work/ratios"
    done
    printf '| %d | %d | %.3g | %.0f | %.3g | %.0f | %.3g | %.0f | %.2f (%s) |\n' "$n" "$np" \
      "$(median <"$work/rate.emergent")" "$(median <"$work/mem.emergent")" \
      "$(median <"$work/rate.lammps")" "$(median <"$work/mem.lammps")" \
      "$(median <"$work/rate.lammps-opt")" "$(median <"$work/mem.lammps-opt")" \
      "$(median <"$work/ratios")" "$(min_max "$work/ratios")" \
      | tee -a "$log.table"
  done
done
{ echo "# table"; cat "$log.table"; } >>"$log"
rm -f "$log.table"
echo "log: $log"

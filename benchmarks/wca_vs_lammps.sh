#!/usr/bin/env bash
# WCA fluid (rho = 0.8, T = 1, dt = 0.005, NVE, skin 0.3) through emergent and LAMMPS, side by
# side: for each size and rank count the two programs alternate, REPEATS times each, and the
# medians of atom-steps/s (timed loop only, after 200 warm-up steps) and their ratio are printed
# as a Markdown table, with peak resident memory per particle (summed over ranks).
#
# usage: benchmarks/wca_vs_lammps.sh [REPEATS] [SIZES] [RANKS]
#   defaults: 3 "20 40" "1 2"   (n_cells 20 -> N = 32000, 40 -> N = 256000)
# Needs build/bin/emergent; LAMMPS (`lmp`, Debian package lammps) is used when installed.
set -euo pipefail
cd "$(dirname "$0")/.."
repeats=${1:-3}
sizes=${2:-"20 40"}
ranks_list=${3:-"1 2"}
exe=$PWD/build/bin/emergent
lmp_input=$PWD/benchmarks/in.wca_bench.lmp
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
have_lmp=0
command -v lmp >/dev/null && have_lmp=1

median() { sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
# Peak RSS of each rank, from GNU time run inside mpirun (one file per rank), summed.
rss_sum() { cat "$1".* | awk '{s+=$1} END {print s*1024}'; rm -f "$1".*; }

printf '| N | ranks | emergent atom-steps/s | B/particle | LAMMPS atom-steps/s | B/particle | emergent/LAMMPS |\n'
printf '|---|---|---|---|---|---|---|\n'
for nc in $sizes; do
  n=$((4 * nc * nc * nc))
  steps=$(( nc >= 40 ? 1000 : 2000 ))
  for np in $ranks_list; do
    : >"$work/e" ; : >"$work/l"; : >"$work/em"; : >"$work/lm"
    for r in $(seq "$repeats"); do
      mpirun --oversubscribe -np "$np" sh -c "/usr/bin/time -f %M -o $work/rss.\$OMPI_COMM_WORLD_RANK \
        $exe run lj-fluid --preset bench --set n_cells=$nc --set steps=$steps \
        --set skin=0.3 --set progress_interval=0 --summary-json $work/s.json" >/dev/null
      grep -o '"atom_steps_per_second": [0-9.e+]*' "$work/s.json" | awk '{print $2}' >>"$work/e"
      echo "$(rss_sum "$work/rss") $n" | awk '{print $1/$2}' >>"$work/em"
      if [ "$have_lmp" = 1 ]; then
        mpirun --oversubscribe -np "$np" sh -c "/usr/bin/time -f %M -o $work/rss.\$OMPI_COMM_WORLD_RANK \
          lmp -in $lmp_input -log $work/lmp.log -screen none -var nc $nc -var nsteps $steps \
          -var skin 0.3" >/dev/null
        loop=$(grep 'Loop time' "$work/lmp.log" | tail -n 1 | awk '{print $4}')
        echo "$n $steps $loop" | awk '{print $1*$2/$3}' >>"$work/l"
        echo "$(rss_sum "$work/rss") $n" | awk '{print $1/$2}' >>"$work/lm"
      fi
    done
    e=$(median <"$work/e"); em=$(median <"$work/em")
    if [ "$have_lmp" = 1 ]; then
      l=$(median <"$work/l"); lm=$(median <"$work/lm")
      ratio=$(echo "$e $l" | awk '{printf "%.2f", $1/$2}')
    else
      l="n/a"; lm="n/a"; ratio="n/a"
    fi
    printf '| %d | %d | %.3g | %.0f | %s | %s | %s |\n' "$n" "$np" "$e" "$em" \
      "$( [ "$l" = n/a ] && echo n/a || printf '%.3g' "$l")" \
      "$( [ "$lm" = n/a ] && echo n/a || printf '%.0f' "$lm")" "$ratio"
  done
done

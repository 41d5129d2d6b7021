#!/usr/bin/env bash
# Peak memory of the WCA benchmark (rho = 0.8, 100 steps after 100) in emergent and LAMMPS,
# side by side: per-rank peak RSS (GNU time inside mpirun) summed over ranks, per atom, at two
# sizes, and the marginal figure (RSS(N2) - RSS(N1)) / (N2 - N1), which leaves out what every
# process costs whatever its size (libraries, MPI). emergent runs twice: as the benchmark runs
# (no output directory), and with -o DIR, where the guards keep a copy of the last good state to
# save if the run goes unstable.
# usage: benchmarks/memory_vs_lammps.sh [SIZES] [RANKS] [LOG]
#   defaults: "40 80" (N = 256000, 2048000) "1 2" benchmarks/logs/memory_vs_lammps_<date>.log
set -euo pipefail
cd "$(dirname "$0")/.."
sizes=${1:-"40 80"}
ranks_list=${2:-"1 2"}
log=${3:-benchmarks/logs/memory_vs_lammps_$(date -u +%Y-%m-%d).log}
source benchmarks/common.sh
command -v lmp >/dev/null || { echo "memory_vs_lammps.sh: needs LAMMPS (apt-get install lammps)" >&2; exit 2; }
export OMP_NUM_THREADS=1
mkdir -p "$(dirname "$log")"

rss_of() {  # NP PROGRAM NC -> summed peak RSS in bytes
  local np=$1 program=$2 nc=$3 cmd
  case $program in
    emergent) cmd="$exe run lj-fluid --preset bench --set n_cells=$nc --set equilibration_steps=100 \
                   --set steps=100 --set skin=0.3 --set progress_interval=0" ;;
    emergent-o) cmd="$exe run lj-fluid --preset bench --set n_cells=$nc --set equilibration_steps=100 \
                   --set steps=100 --set skin=0.3 --set progress_interval=0 -o $work/out --overwrite" ;;
    lammps) cmd="lmp -in $PWD/benchmarks/in.wca_bench.lmp -log none -screen none -var nc $nc \
                 -var nwarm 100 -var nsteps 100 -var skin 0.3" ;;
  esac
  mpirun --oversubscribe -np "$np" sh -c "/usr/bin/time -f %M -o $work/rss.\$OMPI_COMM_WORLD_RANK $cmd" >/dev/null
  rss_sum "$work/rss"
}

{
  echo "# memory_vs_lammps.sh \"$sizes\" \"$ranks_list\""
  build_header
  echo "# each line: ranks N program peak-RSS-bytes(summed over ranks)"
} >"$log"
read -r -a ncs <<<"$sizes"
printf '| ranks | program |'
for nc in "${ncs[@]}"; do printf ' B/atom at N = %d |' $((4 * nc * nc * nc)); done
printf ' marginal B/atom |\n|---|---|'
for nc in "${ncs[@]}"; do printf -- '---|'; done
printf -- '---|\n'
for np in $ranks_list; do
  for program in emergent emergent-o lammps; do
    bytes=()
    for nc in "${ncs[@]}"; do
      b=$(rss_of "$np" "$program" "$nc")
      echo "$np $((4 * nc * nc * nc)) $program $b" >>"$log"
      bytes+=("$b")
    done
    label=$program
    [ "$program" = emergent-o ] && label="emergent with -o (last good state kept)"
    printf '| %d | %s |' "$np" "$label"
    for k in "${!ncs[@]}"; do
      n=$((4 * ncs[k] * ncs[k] * ncs[k]))
      printf ' %.0f |' "$(echo "${bytes[k]} $n" | awk '{print $1/$2}')"
    done
    n1=$((4 * ncs[0] ** 3)); n2=$((4 * ncs[-1] ** 3))
    printf ' %.0f |\n' "$(echo "${bytes[0]} ${bytes[-1]} $n1 $n2" | awk '{print ($2-$1)/($4-$3)}')"
  done
done | tee -a "$work/table"
{ echo "# table"; cat "$work/table"; } >>"$log"
echo "log: $log"

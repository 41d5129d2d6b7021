#!/usr/bin/env bash
# Granular bed (19602 spheres, d = 1, m = pi/6, k_n = 2000, gravity 1, floor, dt = 0.001, skin
# 0.2) through emergent's granular-bed scene and LAMMPS gran/hooke, the same physics on both
# sides: normal spring and damping (LAMMPS gamma_n = 50 on the pair's effective mass = emergent
# gamma_n = 50 m/2), sliding friction min(gamma_s v_t, mu |f_n|) (LAMMPS dampflag 1, gamma_t =
# 25, xmu = 0.5), no sphere rotation (LAMMPS fix nve: omega stays 0), the same floor law.
# What still differs: each program settles its own bed by the same protocol (15 tau from the
# same lattice, different random velocities); LAMMPS computes torques it never uses and runs
# with newton off (its input); LAMMPS has no OPT variant of gran/hooke, so only plain runs.
# Each program settles once; then ROUNDS rounds time 5000 steps after 200 warm-up steps, the
# order alternating from round to round; the table gives the median of the per-round ratios
# with their min-max, peak memory summed over ranks; the raw log goes to LOG.
# usage: benchmarks/granular_vs_lammps.sh [ROUNDS] [RANKS] [LOG]
#   defaults: 5 "1 2" benchmarks/logs/granular_vs_lammps_<date>.log
set -euo pipefail
cd "$(dirname "$0")/.."
rounds=${1:-5}
ranks_list=${2:-"1 2"}
log=${3:-benchmarks/logs/granular_vs_lammps_$(date -u +%Y-%m-%d).log}
source benchmarks/common.sh
command -v lmp >/dev/null || { echo "granular_vs_lammps.sh: needs LAMMPS (apt-get install lammps)" >&2; exit 2; }
export OMP_NUM_THREADS=1
mkdir -p "$(dirname "$log")"
n=19602
skin=0.2
"$exe" run granular-bed --set steps=0 --set skin=$skin --set progress_interval=0 \
  --checkpoint-every 15000 -o "$work/settle" >/dev/null
(cd "$work" && lmp -in "$OLDPWD/benchmarks/in.gran_settle.lmp" -log none -screen none \
   -var out "$work/gran_bed.restart" -var skin $skin)

run_emergent() {  # NP -> "rate bytes"
  mpirun --oversubscribe -np "$1" sh -c "/usr/bin/time -f %M -o $work/rss.\$OMPI_COMM_WORLD_RANK \
    $exe run --restart $work/settle/checkpoint.h5 --set equilibration_steps=15200 --set steps=5000 \
    --set checkpoint_every=0 --set progress_interval=0 -o $work/timed --overwrite --summary-json $work/s.json" >/dev/null
  echo "$(summary_value "$work/s.json" atom_steps_per_second) $(rss_sum "$work/rss")"
}
run_lammps() {  # NP -> "rate bytes"
  (cd "$work" && mpirun --oversubscribe -np "$1" sh -c "/usr/bin/time -f %M -o $work/rss.\$OMPI_COMM_WORLD_RANK \
    lmp -in $OLDPWD/benchmarks/in.gran_bench.lmp -log $work/lmp.log -screen none \
    -var in $work/gran_bed.restart -var skin $skin" >/dev/null)
  local loop
  loop=$(grep 'Loop time' "$work/lmp.log" | tail -n 1 | awk '{print $4}')
  echo "$(echo "$n 5000 $loop" | awk '{printf "%.6g", $1*$2/$3}') $(rss_sum "$work/rss")"
}

{
  echo "# granular_vs_lammps.sh $rounds \"$ranks_list\"  (N = $n, skin $skin)"
  build_header
  echo "# each line: ranks round program atom-steps/s peak-RSS-bytes(summed over ranks)"
} >"$log"
printf '| ranks | emergent atom-steps/s | B/atom | LAMMPS atom-steps/s | B/atom | emergent / LAMMPS: median (min-max) of %d rounds |\n' "$rounds"
printf '|---|---|---|---|---|---|\n'
for np in $ranks_list; do
  : >"$work/ratios"
  for p in emergent lammps; do : >"$work/rate.$p"; : >"$work/mem.$p"; done
  for r in $(seq "$rounds"); do
    order="emergent lammps"
    [ $((r % 2)) -eq 0 ] && order="lammps emergent"
    declare -A rate=()
    for p in $order; do
      read -r rt bytes < <(run_$p "$np")
      echo "$np $r $p $rt $bytes" >>"$log"
      rate[$p]=$rt
      echo "$rt" >>"$work/rate.$p"
      echo "$bytes $n" | awk '{print $1/$2}' >>"$work/mem.$p"
    done
    echo "${rate[emergent]} ${rate[lammps]}" | awk '{print $1 / $2}' >>"$work/ratios"
  done
  printf '| %d | %.3g | %.0f | %.3g | %.0f | %.2f (%s) |\n' "$np" \
    "$(median <"$work/rate.emergent")" "$(median <"$work/mem.emergent")" \
    "$(median <"$work/rate.lammps")" "$(median <"$work/mem.lammps")" \
    "$(median <"$work/ratios")" "$(min_max "$work/ratios")" | tee -a "$work/table"
done
{ echo "# table"; cat "$work/table"; } >>"$log"
echo "log: $log"

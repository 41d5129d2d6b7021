#!/usr/bin/env bash
# Granular bed (19602 spheres, d = 1, k_n = 2000, gravity 1, floor, dt = 0.001): emergent's
# granular-bed scene against LAMMPS gran/hooke (inputs beside this script, as in
# shared/reference), both timed on the same settled bed, alternating, REPEATS runs each; then
# emergent's specialised contact kernel against the generic one on a frictionless, undamped bed.
#
# Model differences (so the ratio compares comparable, not identical, work): LAMMPS integrates
# sphere rotation (nve/sphere) and scales damping by the pair's effective mass; emergent's
# spheres do not rotate (the paper's model) and take gamma in force/velocity, set here to
# LAMMPS's gamma_n = 50, gamma_t = 25 times m_eff = m/2 (m = pi/6).
# usage: benchmarks/granular_vs_lammps.sh [REPEATS] [RANKS]    (defaults 3, "1 2")
set -euo pipefail
cd "$(dirname "$0")/.."
repeats=${1:-3}
ranks_list=${2:-"1 2"}
. benchmarks/common.sh
rss_sum() { cat "$1".* | awk '{s+=$1} END {print s*1024}'; rm -f "$1".*; }
n=19602
# Settle once in each program (15 tau), then time 5000 steps after 200 warm-up steps.
"$exe" run granular-bed --set steps=0 --set progress_interval=0 --checkpoint-every 15000 \
  -o "$work/settle" >/dev/null
have_lmp=0
if command -v lmp >/dev/null; then
  have_lmp=1
  (cd "$work" && lmp -in "$OLDPWD/benchmarks/in.gran_settle.lmp" -log none -screen none \
     -var out "$work/gran_bed.restart")
fi
emergent_run() {  # np label extra-args...
  local np=$1 label=$2; shift 2
  mpirun --oversubscribe -np "$np" sh -c "/usr/bin/time -f %M -o $work/rss.\$OMPI_COMM_WORLD_RANK \
    $exe run --restart $work/settle/checkpoint.h5 --set equilibration_steps=15200 --set steps=5000 \
    --set checkpoint_every=0 --set progress_interval=0 $* --summary-json $work/s.json" >/dev/null
  grep -o '"atom_steps_per_second": [0-9.e+]*' "$work/s.json" | awk '{print $2}' >>"$work/$label"
  echo "$(rss_sum "$work/rss") $n" | awk '{print $1/$2}' >>"$work/$label.mem"
}
printf '| ranks | emergent atom-steps/s | B/particle | LAMMPS atom-steps/s | B/particle | emergent/LAMMPS |\n'
printf '|---|---|---|---|---|---|\n'
for np in $ranks_list; do
  for r in $(seq "$repeats"); do
    emergent_run "$np" "e$np"
    if [ $have_lmp = 1 ]; then
      (cd "$work" && mpirun --oversubscribe -np "$np" sh -c "/usr/bin/time -f %M -o $work/rss.\$OMPI_COMM_WORLD_RANK \
        lmp -in $OLDPWD/benchmarks/in.gran_bench.lmp -log $work/lmp.log -screen none \
        -var in $work/gran_bed.restart" >/dev/null)
      loop=$(grep 'Loop time' "$work/lmp.log" | tail -n 1 | awk '{print $4}')
      echo "$n 5000 $loop" | awk '{print $1*$2/$3}' >>"$work/l$np"
      echo "$(rss_sum "$work/rss") $n" | awk '{print $1/$2}' >>"$work/l$np.mem"
    fi
  done
  e=$(median <"$work/e$np"); em=$(median <"$work/e$np.mem")
  if [ $have_lmp = 1 ]; then
    l=$(median <"$work/l$np"); lm=$(median <"$work/l$np.mem")
    printf '| %d | %.3g | %.0f | %.3g | %.0f | %.2f |\n' "$np" "$e" "$em" "$l" "$lm" "$(echo "$e $l" | awk '{print $1/$2}')"
  else
    printf '| %d | %.3g | %.0f | n/a | n/a | n/a |\n' "$np" "$e" "$em"
  fi
done
# Specialisation: no damping, no friction; the specialised kernel compiles both out.
for r in $(seq "$repeats"); do
  for kernel in specialised generic; do
    emergent_run 1 "k_$kernel" --set gamma_n=0 --set gamma_s=0 --set kernel=$kernel
  done
done
s=$(median <"$work/k_specialised"); g=$(median <"$work/k_generic")
echo
echo "frictionless undamped bed, 1 rank: specialised $s, generic $g atom-steps/s, specialised/generic = $(echo "$s $g" | awk '{printf "%.2f", $1/$2}')"

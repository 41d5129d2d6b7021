# The WCA benchmark's runs, shared by wca_vs_lammps.sh and weak_scaling_vs_lammps.sh (sourced
# after benchmarks/common.sh, with lmp_input set): the same physics through emergent and LAMMPS
# (plain and `-sf opt`), the timed loop only.
steps_for() { echo $(( $1 >= 40 ? 1000 : 2000 )); }

# run_program NAME NP NC: one timed run; prints "rate bytes".
run_program() {
  local name=$1 np=$2 nc=$3 steps
  steps=$(steps_for "$nc")
  local n=$((4 * nc * nc * nc))
  case $name in
    emergent)
      mpirun --oversubscribe -np "$np" sh -c "/usr/bin/time -f %M -o $work/rss.\$OMPI_COMM_WORLD_RANK \
        $exe run lj-fluid --preset bench --set n_cells=$nc --set steps=$steps --set skin=0.3 \
        --set progress_interval=0 --summary-json $work/s.json" >/dev/null
      echo "$(summary_value "$work/s.json" atom_steps_per_second) $(rss_sum "$work/rss")" ;;
    lammps|lammps-opt)
      local suffix=""
      [ "$name" = lammps-opt ] && suffix="-sf opt"
      mpirun --oversubscribe -np "$np" sh -c "/usr/bin/time -f %M -o $work/rss.\$OMPI_COMM_WORLD_RANK \
        lmp $suffix -in $lmp_input -log $work/lmp.log -screen none -var nc $nc -var nsteps $steps \
        -var skin 0.3" >/dev/null
      local loop
      loop=$(grep 'Loop time' "$work/lmp.log" | tail -n 1 | awk '{print $4}')
      echo "$(echo "$n $steps $loop" | awk '{printf "%.6g", $1*$2/$3}') $(rss_sum "$work/rss")" ;;
  esac
}

# Shared by the benchmark scripts (sourced from the repository root): the executable, a scratch
# folder removed on exit, mpirun as root, and the median of numbers on stdin.
exe=$PWD/build/bin/emergent
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
median() { sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }

# scene_sweep OUT_DIR RANKS STEPS KEY VALUE... -- SCENE_ARGS...: one run of SCENE_ARGS per
# value of KEY, into OUT_DIR/KEY_VALUE; runs already complete there are kept, so a sweep that
# was stopped continues where it was.
scene_sweep() {
  local out=$1 ranks=$2 steps=$3 key=$4 values=() v
  shift 4
  while [ "$1" != "--" ]; do values+=("$1"); shift; done
  shift
  mkdir -p "$out"
  for v in "${values[@]}"; do
    [ -f "$out/${key}_$v/summary.json" ] && continue
    mpirun -q --oversubscribe -np "$ranks" "$exe" run "$@" --set "$key=$v" --set steps="$steps" \
      --set progress_interval=0 -o "$out/${key}_$v" >/dev/null
  done
}

# settle_checkpoint EXE RANKS STEPS SCENE_ARGS...: runs the scene STEPS steps once into
# $work/settle and leaves $work/settle/checkpoint.h5, the state timed runs continue from.
settle_checkpoint() {
  local exe_=$1 ranks_=$2 steps_=$3
  shift 3
  mpirun --oversubscribe -np "$ranks_" "$exe_" run "$@" --set steps="$steps_" \
    --set equilibration_steps=0 --set checkpoint_every="$steps_" --set output.every=0 \
    --set progress_interval=0 -o "$work/settle" >/dev/null
}

# summary_value FILE KEY: a number from a run's summary JSON.
summary_value() { grep -o "\"$2\": [0-9.e+-]*" "$1" | awk '{print $2}'; }

# Shared by the benchmark scripts (sourced from the repository root): the executable, a scratch
# folder removed on exit, mpirun as root, and the median of numbers on stdin.
exe=${EMERGENT_EXE:-$PWD/build/bin/emergent}  # EMERGENT_EXE: a copy, so that a rebuild cannot change a benchmark midway
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
median() { sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }

# start_or_resume DIR SCENE_ARGS...: sets run_args, what `emergent run` is given before -o DIR in
# a sweep that keeps the runs already complete in DIR (summary.json: the caller skips those).
# Into a DIR without a run: SCENE_ARGS. Where a run there stopped before its end and left
# DIR/checkpoint.h5 (Ctrl-C and SIGTERM write one, as does checkpoint_every): --restart from it,
# the same run continued with its own settings (its summary's wall_seconds then count the
# continuation alone). A run there with no checkpoint stops the script with one line, its files
# untouched: the engine would refuse to write over them, and they are the user's to keep or
# remove.
start_or_resume() {
  local dir=$1
  shift
  if [ -f "$dir/checkpoint.h5" ]; then
    run_args=(--restart "$dir/checkpoint.h5")
  elif compgen -G "$dir/trajectory*.h5" >/dev/null; then
    echo "$(basename "$0"): $dir holds an unfinished run without a checkpoint to continue from:" \
      "move it away (or remove it) to run it again" >&2
    exit 2
  else
    run_args=("$@")
  fi
}

# scene_sweep OUT_DIR RANKS STEPS KEY VALUE... -- SCENE_ARGS...: one run of SCENE_ARGS per
# value of KEY, into OUT_DIR/KEY_VALUE; runs already complete there are kept and stopped ones
# continued (start_or_resume), so a sweep that was stopped continues where it was.
scene_sweep() {
  local out=$1 ranks=$2 steps=$3 key=$4 values=() v
  shift 4
  while [ "$1" != "--" ]; do values+=("$1"); shift; done
  shift
  mkdir -p "$out"
  for v in "${values[@]}"; do
    [ -f "$out/${key}_$v/summary.json" ] && continue
    start_or_resume "$out/${key}_$v" "$@" --set "$key=$v" --set steps="$steps" --set progress_interval=0
    mpirun -q --oversubscribe -np "$ranks" "$exe" run "${run_args[@]}" -o "$out/${key}_$v" >/dev/null
  done
}

# settle_checkpoint EXE RANKS STEPS SCENE_ARGS...: runs the scene STEPS steps once into
# $work/settle and leaves $work/settle/checkpoint.h5, the state timed runs continue from. Each
# timed run writes elsewhere (-o "$work/timed" --overwrite): beside the checkpoint, a second
# continuation from its step would find the first one's trajectory.from<STEP>.h5 and be refused.
settle_checkpoint() {
  local exe_=$1 ranks_=$2 steps_=$3
  shift 3
  mpirun --oversubscribe -np "$ranks_" "$exe_" run "$@" --set steps="$steps_" \
    --set equilibration_steps=0 --set checkpoint_every="$steps_" --set output.every=0 \
    --set progress_interval=0 -o "$work/settle" >/dev/null
}

# summary_value FILE KEY: a number from a run's summary JSON.
summary_value() { grep -o "\"$2\": [0-9.e+-]*" "$1" | awk '{print $2}'; }

# rss_sum PREFIX: peak RSS of each rank (one file PREFIX.<rank> per rank, written by GNU time
# -f %M inside mpirun), summed, in bytes; the files are removed.
rss_sum() { cat "$1".* | awk '{s+=$1} END {print s*1024}'; rm -f "$1".*; }

# min_max FILE: "min-max" of the numbers in FILE.
min_max() { sort -g "$1" | awk -v d="${2:-2}" 'NR==1 {lo=$1} {hi=$1} END {printf "%.*f-%.*f", d, lo, d, hi}'; }

# run_stamp: when and where a run-length benchmark ran ("<UTC time>; <cores> cores, <CPU>");
# commit_line: "# commit <hash>", marked when the engine's sources differ from it.
run_stamp() { echo "$(date -u +%FT%TZ); $(nproc) cores, $(lscpu | sed -n 's/^Model name: *//p' | head -n 1)"; }
commit_line() {
  echo "# commit $(git rev-parse --short=12 HEAD)$(git diff --quiet HEAD -- src include problems || echo ' (modified)')"
}

# build_header: what a benchmark log records of the machine and both programs' builds.
build_header() {
  echo "# machine: $(getconf _NPROCESSORS_ONLN) cores, $(lscpu | sed -n 's/^Model name: *//p' | head -n 1), $(free -g | awk '/Mem:/ {print $2}') GiB; $(date -u +%FT%TZ)"
  echo "# emergent: commit $(git rev-parse --short HEAD)$(git diff --quiet HEAD -- src include decomposition problems || echo ' (modified)'),"\
       "$(grep -E '^CMAKE_BUILD_TYPE:' build/CMakeCache.txt | cut -d= -f2) build, CXX flags" \
       "'$(grep -E '^CMAKE_CXX_FLAGS_RELEASE:' build/CMakeCache.txt | cut -d= -f2)'" \
       "$(grep -q '^EMERGENT_CPU_HAS_AVX2:INTERNAL=1' build/CMakeCache.txt && echo '-march=x86-64-v3' || echo '(generic x86-64)')," \
       "g++ $(g++ -dumpfullversion)"
  if command -v lmp >/dev/null; then
    echo "# LAMMPS: $(lmp -h | sed -n 's/^Large-scale Atomic.Molecular Massively Parallel Simulator - //p' | head -n 1), Debian package lammps" \
         "$(dpkg-query -W -f='${Version}' lammps 2>/dev/null); $(lmp -h | grep -m1 '^Compiler:');" \
         "built with Debian's package flags ($(dpkg-buildflags --get CXXFLAGS 2>/dev/null | awk '{print $1, $2}') ...)"
  fi
}

# steps_for TIME DT: the whole number of steps (at least 1) nearest to TIME time units at step
# DT; a DT or TIME that is not a positive number stops the script with one line (exit 2).
steps_for() {
  /usr/bin/python3 -c "
import sys
try:
    t, dt = float(sys.argv[1]), float(sys.argv[2])
    assert t > 0 and dt > 0
except (ValueError, AssertionError):
    sys.exit(f'time {sys.argv[1]!r} and step {sys.argv[2]!r} must be positive numbers')
print(max(1, round(t / dt)))" "$1" "$2" || exit 2
}

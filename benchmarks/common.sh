# Shared by the benchmark scripts (sourced from the repository root): the executable, a scratch
# folder removed on exit, mpirun as root, and the median of numbers on stdin.
exe=$PWD/build/bin/emergent
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
median() { sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }

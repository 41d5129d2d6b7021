#!/usr/bin/env bash
# The openings of the near-complete capsomer clusters in the long runs' saved states, and what
# lies over them (scripts/capsid_holes): each checkpoint is continued 10 steps on one rank, so
# the continuation's first frame carries the bond census (checkpoints keep no cluster ids), and
# that frame is read against the closed shell of a `start=shell` run of the default design.
# usage: benchmarks/capsid_holes.sh MIN RUN_DIR...     (MIN: the smallest cluster looked at,
#   e.g. 51; RUN_DIR: a folder with checkpoint.h5, e.g. benchmarks/logs/capsid_long/*)
#   A RUN_DIR that also holds trajectories (a run in progress) is read over all its body frames.
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -ge 2 ] || { sed -n 2,8p "$0"; exit 2; }
. benchmarks/common.sh
smallest=$1
shift
echo "# $(date -u +%F) $(git rev-parse --short HEAD); $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')"
"$exe" run capsid-assembly --preset tiny --set steps=0 --set progress_interval=0 -o "$work/shell" >/dev/null
for run in "$@"; do
  if compgen -G "$run/trajectory*.h5" >/dev/null; then
    scripts/capsid_holes "$run" "$work/shell" "$smallest"
    continue
  fi
  [ -f "$run/checkpoint.h5" ] || { echo "capsid_holes.sh: no checkpoint.h5 in $run" >&2; exit 2; }
  dir=$work/$(basename "$run")
  mkdir -p "$dir" && cp "$run/checkpoint.h5" "$dir/"
  step=$(/usr/bin/python3 -c "import h5py; print(int(h5py.File('$dir/checkpoint.h5', 'r')['checkpoint'].attrs['step']))")
  "$exe" run --restart "$dir/checkpoint.h5" --set steps=$((step + 10)) --set checkpoint_every=0 \
    --set progress_interval=0 -o "$dir" >/dev/null
  echo "## $run (step $step)"
  scripts/capsid_holes "$dir" "$work/shell" "$smallest" 0 | sed "s|$work/||"
done

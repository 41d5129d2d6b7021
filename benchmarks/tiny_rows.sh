#!/usr/bin/env bash
# Every scene's `tiny` run on the host and checking back ends, on 1 and 2 ranks: its thermo
# rows (thermo.dat) into OUT/SCENE_BACKEND_npN.dat. Two builds' folders compared with
# `diff -r` show whether a change of the engine changed what it computes, digit for digit.
# usage: benchmarks/tiny_rows.sh OUT   (EMERGENT_EXE: the binary, default build/bin/emergent)
set -euo pipefail
cd "$(dirname "$0")/.."
. benchmarks/common.sh
out=${1:?usage: benchmarks/tiny_rows.sh OUT}
mkdir -p "$out"
scenes=$("$exe" list | awk '{print $1}')
for scene in $scenes; do
  for backend in host checking; do
    for np in 1 2; do
      run=$work/$scene.$backend.$np
      mpirun -q --oversubscribe -np $np "$exe" run "$scene" --preset tiny --set backend=$backend \
        --set progress_interval=0 -o "$run" >/dev/null
      cp "$run/thermo.dat" "$out/${scene}_${backend}_np$np.dat"
    done
  done
done
echo "tiny_rows.sh: $(ls "$out" | wc -l) runs' rows in $out"

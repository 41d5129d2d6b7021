#!/usr/bin/env bash
# The one script a lent GPU machine runs (at most 5 minutes on one H100/H200), from the bundle
# that benchmarks/gpu_bundle.sh packed and tried here:
#   tests       gpu_tests: the execution layer's CUDA reductions, scans and sorts against the
#               host's; the engine on cuda (Simulation, backend=cuda) against an all-pairs
#               reference, its energy drift, bitwise repeats, guards, the WCA state point
#               against LAMMPS
#   sanitizer   compute-sanitizer memcheck, racecheck and initcheck on the execution-layer tests and a
#               tiny engine run (said so where the machine has no sanitizer or refuses it)
#   scenes      every scene's tiny preset through Simulation with backend=cuda against
#               backend=host (same list layout): the first sampled row must agree to 1e-6
#               relative (round-off is ~1e-15 there; a wrong or unsynced kernel is O(1)), and
#               the rows after it are printed (where chaos or a discrete event separates the
#               runs); cuda run twice gives the same thermo.dat; 2 ranks sharing the GPU
#               against 1 rank; a checkpoint written on cuda continued on host; a guard firing
#               on the device (exit 3, its message, last_good.h5)
#   throughput  WCA at rho 0.8, 1 million atoms by `emergent run lj-fluid backend=cuda`, and
#               where the bundle has it (REFERENCE=1 benchmarks/gpu_bundle.sh) by the separate
#               pair system the engine replaced (3.7e9 atom-steps/s on an H100: the figure the
#               engine must keep); taylor-couette paper, rayleigh-benard medium,
#               rotating-drum short and capsid-assembly table1 (explicit solvent, 244625
#               particles: the rate its projected days rest on), set-up plus a few hundred steps
#               on cuda, with the device memory per particle
#   scaling     weak scaling of lj-fluid on the host back end, 1 to 16 ranks (the machine's 16
#               cores), in the time left of the 5 minutes (the other parts' limits add up to
#               320 s; most finish well inside them)
# A failed device test or run is repeated with CUDA_LAUNCH_BLOCKING=1, so the error names the
# loop's functor.
#   profile     (only when asked for: --only profile) the throughput cases with
#               EMERGENT_PROFILE=1: the device's time by loop, reduction, scan, sort and copy
#   ratio       (only when asked for) lj-fluid WCA at 1M atoms on the engine against the
#               separate path it replaced, 5 alternating rounds, median ratio with min-max
# usage: bash benchmarks/gpu_check.sh [--only tests|scenes|sanitizer|throughput|scaling|profile|ratio]
#        [--bundle DIR]
#   DIR defaults to gpu_bundle/, else gpu_bundle.tar.xz is unpacked (what travels).
# The log goes to $OUT/gpu_check.log where the device tool sets OUT (copy it to
# benchmarks/logs/), else to benchmarks/logs/gpu_check_<date>.log. Each part has its own time
# limit; the exit status is that of the first part that failed (124: it ran out of time), 2 for
# a bad argument or setting (one line naming it).
set -uo pipefail
cd "$(dirname "$0")/.."
only="" bundle=gpu_bundle
while [ $# -gt 0 ]; do
  case $1 in
    --only) only=${2:?--only needs tests, scenes, sanitizer, throughput, scaling, profile or ratio}; shift 2 ;;
    --bundle) bundle=${2:?--bundle needs a directory}; shift 2 ;;
    *) echo "gpu_check.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
case $only in ""|tests|scenes|sanitizer|throughput|scaling|profile|ratio) ;; *) echo "gpu_check.sh: no part '$only'" >&2; exit 2 ;; esac
for v in SCALING_CELLS SCALING_STEPS SCALING_SECONDS; do
  [[ -z "${!v:-}" || "${!v}" =~ ^[1-9][0-9]*$ ]] ||
    { echo "gpu_check.sh: $v=${!v} is not a positive whole number" >&2; exit 2; }
done
if [ ! -d "$bundle" ] && [ -f "$bundle.tar.xz" ]; then
  mkdir -p /tmp/emergent_bundle && tar -xJf "$bundle.tar.xz" -C /tmp/emergent_bundle ||
    { echo "gpu_check.sh: cannot unpack $bundle.tar.xz" >&2; exit 2; }
  bundle=/tmp/emergent_bundle/$(basename "$bundle")
fi
[ -x "$bundle/bin/gpu_tests" ] || { echo "gpu_check.sh: no bundle at $bundle (benchmarks/gpu_bundle.sh)" >&2; exit 2; }
# A bundle from other code than this tree's would measure the wrong thing: said in the log.
# (Not a refusal: the device tool's copy of the tree may carry an older .git than its files.)
packed=$(sed -n 's/^commit //p' "$bundle/MANIFEST" | cut -d' ' -f1)
here=$(git rev-parse --short=12 HEAD 2>/dev/null || true)
bundle_note=""
[ -n "$here" ] && [ "$packed" != "$here" ] &&
  bundle_note="# note: the bundle is from $packed, this tree's git says $here (benchmarks/gpu_bundle.sh packs the tree's build)"
bundle=$(realpath "$bundle")
# shellcheck source=/dev/null
source "$bundle/bundle_env.sh"
bin=$bundle/bin
log=${OUT:+$OUT/gpu_check${only:+_$only}.log}
log=${log:-benchmarks/logs/gpu_check${only:+_$only}_$(date -u +%Y-%m-%d).log}
mkdir -p "$(dirname "$log")"
exec > >(tee "$log") 2>&1

script_start=$(date +%s)
echo "# gpu_check.sh ${only:-all parts}; $(date -u +%FT%TZ)"
sed 's/^/# bundle: /' "$bundle/MANIFEST" | head -n 3
[ -n "$bundle_note" ] && echo "$bundle_note"
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv,noheader 2>&1 |
  sed 's/^/# device: /'
echo "# host: $(nproc) cores, $(lscpu | sed -n 's/^Model name: *//p' | head -n 1)"

status=0
part() {  # NAME LIMIT_S COMMAND...
  local name=$1 limit=$2 start rc
  shift 2
  echo "## $name (limit ${limit} s): $*"
  start=$(date +%s)
  # Through bash, so a part may be one of this script's (exported) functions.
  timeout "$limit" bash -c '"$@"' part "$@"
  rc=$?
  echo "## $name: exit $rc after $(( $(date +%s) - start )) s"
  [ $rc -ne 0 ] && [ $status -eq 0 ] && status=$rc
  return 0
}

# On the device every GPU test must run: a skip there means the device was not seen (e.g. a
# driver older than the bundle's CUDA runtime), not a pass.
device_tests() {
  local out rc
  out=$("$bin/gpu_tests" --gtest_brief=1 --gtest_filter='-*RefusesClearly*' "$@" 2>&1)
  rc=$?
  echo "$out"
  # A kernel's error is sticky: the tests after the first failure fail with it. Each failed
  # test again alone, with blocking launches, so the error names the loop (its functor).
  local failed t
  failed=$(sed -n 's/^\[  FAILED  \] \([A-Za-z0-9_/.]*\).*/\1/p' <<<"$out" | sort -u | head -n 6)
  for t in $failed; do
    echo "### $t alone, CUDA_LAUNCH_BLOCKING=1:"
    CUDA_LAUNCH_BLOCKING=1 "$bin/gpu_tests" --gtest_brief=1 --gtest_filter="$t" 2>&1 | tail -n 8
  done
  if grep -q "SKIPPED" <<<"$out"; then
    local driver
    driver=$(head -n 1 /proc/driver/nvidia/version 2>/dev/null)
    echo "gpu_check.sh: GPU tests were skipped: no usable device seen (driver: ${driver:-none found})"
    return 3
  fi
  return $rc
}

export -f device_tests
export bin
if [ -z "$only" ] || [ "$only" = tests ]; then
  part "gpu tests" 45 device_tests
fi

# thermo.dat of run A against run B: per row "step:largest relative difference" of the
# columns after step and time (relative to the larger magnitude, floored at 1e-6 so momenta
# near zero compare absolutely); the last line is "first D last D".
compare_thermo() {
  awk 'FNR == 1 { file++ } /^#/ { next }
       file == 1 { for (i = 3; i <= NF; i++) a[FNR, i] = $i; next }
       { m = 0
         for (i = 3; i <= NF; i++) {
           x = a[FNR, i]; y = $i; d = x - y; if (d < 0) d = -d
           s = x < 0 ? -x : x; t = y < 0 ? -y : y; if (t > s) s = t; if (s < 1e-6) s = 1e-6
           if (d / s > m) m = d / s }
         printf "%s:%.1e ", $1, m; if (!seen++) first = m; last = m }
       END { printf "\nfirst %.3e last %.3e\n", first, last }' "$1" "$2"
}
# thermo.dat FILE holds at least one row (a run that ended without output fails, not passes).
has_rows() { [ -f "$1" ] && grep -qv '^#' "$1"; }
scene_checks() {
  local dir rc=0 scene layout out first
  dir=$(mktemp -d)
  # From step 0 (no equilibration), so the first row compares forces and energies of the same
  # state: only the order of additions differs there.
  # A failed device run is run again with blocking launches, so its error names the loop; the
  # second run replaces the failed one's files (its -o DIR is among the arguments).
  run1() {
    timeout 40 emergent run "$@" --preset tiny --set equilibration_steps=0 --set progress_interval=0 \
      >/dev/null 2>"$dir/err" && return 0
    tail -n 3 "$dir/err"
    if grep -q "backend=$dev" <<<"$*"; then
      CUDA_LAUNCH_BLOCKING=1 timeout 40 emergent run "$@" --preset tiny --set equilibration_steps=0 \
        --set progress_interval=0 --overwrite >/dev/null 2>"$dir/err"
      echo "  again with CUDA_LAUNCH_BLOCKING=1: exit $?: $(tail -n 2 "$dir/err")"
    fi
    return 1
  }
  for scene in lj-fluid granular-bed planar-couette rayleigh-benard rotating-drum taylor-couette \
               vibrated-sawtooth capsid-assembly; do
    layout=full  # every scene's force terms have a back-end form
    local extra=()
    [ $scene = vibrated-sawtooth ] && extra=(--set steps=5000 --set big_fraction=0.3)
    for backend in host $dev ${dev}2; do
      run1 "$scene" "${extra[@]}" --set backend=${backend%2} --set neighbour_list=$layout -o "$dir/$scene.$backend" ||
        { echo "$scene: $backend run failed"; rc=1; continue 2; }
      has_rows "$dir/$scene.$backend/thermo.dat" ||
        { echo "$scene: FAIL the $backend run left no thermo rows"; rc=1; continue 2; }
    done
    out=$(compare_thermo "$dir/$scene.host/thermo.dat" "$dir/$scene.$dev/thermo.dat")
    first=$(tail -n 1 <<<"$out" | awk '{print $2}')
    echo "$scene host vs $dev: $out"
    awk -v d="$first" 'BEGIN { exit !(d < 1e-6) }' || { echo "$scene: FAIL host and $dev differ at the first row"; rc=1; }
    cmp -s "$dir/$scene.$dev/thermo.dat" "$dir/$scene.${dev}2/thermo.dat" ||
      { echo "$scene: FAIL two $dev runs differ"; rc=1; }
  done
  # 2 ranks sharing the GPU against 1 rank (a different summation order: round-off apart).
  for scene in lj-fluid taylor-couette; do
    timeout 40 mpirun -q --oversubscribe -np 2 emergent run "$scene" --preset tiny --set progress_interval=0 \
      --set equilibration_steps=0 \
      --set backend=$dev --set neighbour_list=full -o "$dir/$scene.$dev.np2" >/dev/null 2>"$dir/err" ||
      { cat "$dir/err"; echo "$scene: FAIL on 2 ranks"; rc=1; continue; }
    has_rows "$dir/$scene.$dev.np2/thermo.dat" || { echo "$scene: FAIL no thermo rows on 2 ranks"; rc=1; continue; }
    out=$(compare_thermo "$dir/$scene.$dev/thermo.dat" "$dir/$scene.$dev.np2/thermo.dat")
    echo "$scene $dev 1 rank vs 2 ranks: $out"
    first=$(tail -n 1 <<<"$out" | awk '{print $2}')
    awk -v d="$first" 'BEGIN { exit !(d < 1e-6) }' || { echo "$scene: FAIL 1 and 2 ranks differ at the first row"; rc=1; }
  done
  # A checkpoint written on cuda, continued on host, against a straight host run.
  local restart=(--set n_cells=6 --set equilibration_steps=100 --set sample_every=20
                 --set progress_interval=0 --set neighbour_list=full)
  timeout 40 emergent run lj-fluid "${restart[@]}" --set steps=300 --set backend=host -o "$dir/straight" >/dev/null 2>&1 &&
  timeout 40 emergent run lj-fluid "${restart[@]}" --set steps=150 --set backend=$dev --checkpoint-every 250 \
    -o "$dir/across" >/dev/null 2>&1 &&
  timeout 40 emergent run --restart "$dir/across/checkpoint.h5" --set steps=300 --set checkpoint_every=0 \
    --set backend=host -o "$dir/across" >/dev/null 2>&1 ||
    { echo "restart across back ends: FAIL (a run failed)"; rc=1; }
  # The same steps, and rows within round-off grown by 150 steps of chaos (measured 1e-12 to
  # 1e-10 where the device and the host sum in other orders; a broken restart is off by 1e-3
  # and more): the largest relative difference of any row under 1e-6.
  echo "restart $dev -> host: last rows $(tail -n 1 "$dir/straight/thermo.dat" | cut -d' ' -f1-6) |" \
       "$(tail -n 1 "$dir/across/thermo.dat" | cut -d' ' -f1-6)"
  if ! has_rows "$dir/straight/thermo.dat" || ! has_rows "$dir/across/thermo.dat" ||
     [ "$(grep -v '^#' "$dir/straight/thermo.dat" | cut -d' ' -f1)" != "$(grep -v '^#' "$dir/across/thermo.dat" | cut -d' ' -f1)" ]; then
    echo "restart across back ends: FAIL the continued run's rows are not the straight run's steps"; rc=1
  else
    out=$(compare_thermo "$dir/straight/thermo.dat" "$dir/across/thermo.dat")
    echo "restart $dev -> host against straight host: $(tail -n 1 <<<"$out")"
    worst=$(head -n 1 <<<"$out" | tr ' ' '\n' | awk -F: 'NF == 2 && $2 + 0 > m { m = $2 + 0 } END { print m + 0 }')
    awk -v d="$worst" 'BEGIN { exit !(d < 1e-6) }' ||
      { echo "restart across back ends: FAIL rows differ by $worst (relative)"; rc=1; }
  fi
  # A guard firing on the device: exit 3, one line, the last good state kept.
  timeout 40 emergent run lj-fluid --preset tiny --set backend=$dev --set guard.max_force=1 -o "$dir/guard" \
    >/dev/null 2>"$dir/err"
  local code=$?
  if [ $code -eq 3 ] && grep -q "exceeds guard.max_force" "$dir/err" && [ -f "$dir/guard/last_good.h5" ]; then
    echo "guard on the device: stopped with exit 3: $(tail -n 1 "$dir/err")"
  else
    echo "guard on the device: FAIL (exit $code: $(tail -n 1 "$dir/err"))"; rc=1
  fi
  rm -rf "$dir"
  return $rc
}
# GPU_CHECK_BACKEND=checking runs the scenes part on a machine without a device (to try the
# script itself; the checking back end is bitwise the host's, so every difference is 0).
dev=${GPU_CHECK_BACKEND:-cuda}
export -f compare_thermo has_rows scene_checks
export dev
if [ -z "$only" ] || [ "$only" = scenes ]; then
  part "scenes host vs $dev" 75 scene_checks
fi

if [ -z "$only" ] || [ "$only" = sanitizer ]; then
  sanitizer=$(command -v compute-sanitizer || ls /usr/local/cuda/bin/compute-sanitizer 2>/dev/null || true)
  if [ -z "$sanitizer" ]; then
    echo "## sanitizer: compute-sanitizer is not on this machine; not run"
  else
    # The small cases only (tens of thousands of particles): the sanitizer slows kernels 10-100x.
    # initcheck: a kernel that reads device memory nothing wrote (the checking back end
    # poisons its allocations for the same on a CPU).
    for tool in memcheck racecheck initcheck; do
      part "sanitizer $tool" 15 "$sanitizer" --tool "$tool" --error-exitcode 99 \
        "$bin/gpu_tests" --gtest_brief=1 --gtest_filter='DeviceFunctors.*:CudaEngine.StopsWithAClearMessageWhenTheRunBlowsUp'
    done
    part "sanitizer memcheck, scenes" 20 bash -c 'for s in lj-fluid rayleigh-benard taylor-couette; do
      "$0" --tool memcheck --error-exitcode 99 emergent run $s --preset tiny --set backend=cuda \
        --set neighbour_list=full --set steps=100 --set progress_interval=0 -o /tmp/san.$s --overwrite >/dev/null || exit; done' "$sanitizer"
  fi
fi

# The throughput cases, shared by the throughput, ratio and profile parts: lj-fluid WCA at 1M
# atoms (and the separate path's benchmark of the same physics), the flow scenes' paper-scale
# presets for a few hundred steps.
reference_args="--cells 63 --density 0.8 --skin 0.3 --steps 500 --warmup 500 --repeats 3 --precision double"
wca=(lj-fluid --set n_cells=63 --set thermostat=none --set equilibration_steps=100 --set steps=500
     --set sample_every=500 --set guard.every=500)
taylor=(taylor-couette --preset paper --set steps=300 --set sample_every=300 --set fields.interval=0
        --set output.every=0)
layer=(rayleigh-benard --preset medium --set steps=200 --set sample_every=200 --set fields.interval=0
       --set output.every=0)
drum=(rotating-drum --preset short --set steps=300 --set sample_every=300 --set output.every=0
      --set checkpoint_every=0)
capsid=(capsid-assembly --preset table1 --set steps=500 --set sample_every=500 --set output.every=0
        --set checkpoint_every=0)
# emergent run on cuda, its rate, memory and time split from the summary (and on stderr the
# device profile where EMERGENT_PROFILE is set). Its output folder in /tmp is scratch, replaced
# by the next run of the same case (the ratio's rounds; this script again on a warm machine).
engine_case() {  # JSON SCENE_ARGS...
  local json=$1
  shift
  emergent run "$@" --set progress_interval=0 --set backend=cuda --set neighbour_list=full \
    --summary-json "$json" -o "/tmp/throughput.$(basename "$json" .json)" --overwrite >/dev/null || return
  grep -E '"(N|steps|wall_seconds|atom_steps_per_second|device_bytes_per_particle|bytes_per_particle|neighbour_rebuilds|seconds_(force|neighbour|integrate|communicate))"' "$json" | tr -d ' \n'
  echo
}
export -f engine_case
export reference_args

if [ -z "$only" ] || [ "$only" = throughput ]; then
  # One round each within the 5 minutes (the ratio needs alternating rounds: --only ratio).
  if [ -x "$bin/emergent-gpu-bench" ]; then
    # shellcheck disable=SC2086
    part "throughput WCA 1M double, the separate path the engine replaced" 20 "$bin/emergent-gpu-bench" $reference_args
  else
    echo "## throughput of the separate path: not in this bundle (REFERENCE=1 benchmarks/gpu_bundle.sh)"
  fi
  part "throughput WCA 1M double, Simulation backend=cuda" 25 engine_case /tmp/wca.json "${wca[@]}"
  part "throughput taylor-couette paper (set-up + 300 steps)" 25 engine_case /tmp/tc.json "${taylor[@]}"
  part "throughput rayleigh-benard medium (set-up + 200 steps)" 30 engine_case /tmp/rb.json "${layer[@]}"
  part "throughput rotating-drum short (set-up + 300 steps)" 25 engine_case /tmp/drum.json "${drum[@]}"
  part "throughput capsid-assembly table1, explicit solvent (set-up + 500 steps)" 25 engine_case /tmp/capsid.json "${capsid[@]}"
fi

# The engine against the separate path it replaced, WCA at 1M atoms: 5 rounds, alternating
# which runs first, the median of the per-round ratios with min and max (only with --only ratio).
if [ "$only" = ratio ]; then
  ratio_rounds() {  # ENGINE_SCENE_ARGS...
    local r ref eng first ratios=()
    for r in 1 2 3 4 5; do
      for first in $( [ $((r % 2)) = 1 ] && echo "ref eng" || echo "eng ref"); do
        if [ $first = ref ]; then
          # shellcheck disable=SC2086
          ref=$("$bin/emergent-gpu-bench" $reference_args | sed -n 's/.*atom_steps_per_s=\([0-9.e+]*\).*/\1/p')
        else
          engine_case /tmp/ratio.json "$@" >/dev/null || return
          eng=$(sed -n 's/.*"atom_steps_per_second": \([0-9.e+]*\).*/\1/p' /tmp/ratio.json)
        fi
      done
      ratios+=("$(awk -v a="$eng" -v b="$ref" 'BEGIN { printf "%.3f", a / b }')")
      echo "round $r: separate path $ref, engine $eng atom-steps/s, ratio ${ratios[-1]}"
    done
    printf '%s\n' "${ratios[@]}" | sort -g |
      awk '{ a[NR] = $1 } END { printf "median %.3f (min %.3f, max %.3f)\n", a[3], a[1], a[5] }'
  }
  export -f ratio_rounds
  part "WCA 1M: engine / separate path, 5 alternating rounds" 90 ratio_rounds "${wca[@]}" \
    --set steps=1000 --set sample_every=1000 --set guard.every=1000
fi

# Where the device's time goes (only with --only profile: each call is timed alone, so the run
# is slower): the throughput cases with EMERGENT_PROFILE=1, the table of loops, reductions,
# scans, sorts and copies by functor, each beside the case's unprofiled rate above.
if [ "$only" = profile ]; then
  echo "# profilers on this machine: $(command -v nsys ncu 2>/dev/null | tr '\n' ' ')$(ls -d /opt/nvidia/nsight* /usr/local/cuda/nsight* 2>/dev/null | tr '\n' ' ')"
  export EMERGENT_PROFILE=1
  part "profile WCA 1M" 40 engine_case /tmp/profile.wca.json "${wca[@]}" --set equilibration_steps=0
  part "profile rotating-drum short" 40 engine_case /tmp/profile.drum.json "${drum[@]}"
  part "profile rayleigh-benard medium" 40 engine_case /tmp/profile.rb.json "${layer[@]}"
  part "profile capsid-assembly table1" 40 engine_case /tmp/profile.capsid.json "${capsid[@]}"
  unset EMERGENT_PROFILE
fi

# Weak scaling of lj-fluid on the host back end, 1 to 16 ranks (one per core here: real
# scaling, unlike 2 cores oversubscribed), 4 SCALING_CELLS^3 atoms per rank (default 16: 16384),
# SCALING_STEPS timed steps (default 800), rounds in alternating order
# for the time left of the 5 minutes. The runs' JSON go to $OUT/scaling_weak;
# TABLE_ONLY=1 CORES=<cores> OUT=<that folder> ROUNDS=<rounds> benchmarks/scaling.sh weak
# lj-fluid 1 2 4 8 16 -- --set n_cells=<SCALING_CELLS> tabulates them.
scaling_runs() {  # SECONDS_LEFT
  local deadline=$(( $(date +%s) + $1 )) out=${OUT:-/tmp}/scaling_weak round np cells t0 took=0
  local base=${SCALING_CELLS:-16} steps=${SCALING_STEPS:-800}
  local ranks=(1 2 4 8 16)
  [ "$(nproc)" -ge 16 ] || ranks=(1 2)
  mkdir -p "$out"
  for round in 1 2 3 4 5; do
    t0=$(date +%s)
    [ $(( t0 + took + 5 )) -lt "$deadline" ] || break
    local order=("${ranks[@]}")
    [ $((round % 2)) = 0 ] && order=($(printf '%s\n' "${ranks[@]}" | sort -rn))
    for np in "${order[@]}"; do
      cells=$(awk -v n="$np" -v c="$base" 'BEGIN { printf "%d", c * n ^ (1 / 3) + 0.5 }')
      mpirun -q --bind-to core -np "$np" emergent run lj-fluid --set n_cells="$cells" \
        --set backend=host --set equilibration_steps=$((steps / 4)) --set steps=$steps --set progress_interval=0 \
        --summary-json "$out/np${np}_round$round.json" >/dev/null || return
      grep -hoE '"(N|grid|wall_seconds|atom_steps_per_second)": [^,]*' "$out/np${np}_round$round.json" |
        tr '\n' ' ' | sed "s/^/round $round, $np ranks: /"
      echo
    done
    took=$(( $(date +%s) - t0 ))
    echo "rounds complete: $round"
  done
  # The machine's own slowdown when all cores work (shared memory bandwidth, caches, SMT), with
  # no communication: as many independent 1-rank runs at once as the largest rank count, each
  # on its core; scaling.sh divides the efficiency by it.
  local n=${ranks[-1]} k
  for round in 1 2 3; do
    [ $(( $(date +%s) + 8 )) -lt "$deadline" ] || break
    for ((k = 0; k < n; ++k)); do
      taskset -c "$k" emergent run lj-fluid --set n_cells=$base --set backend=host \
        --set equilibration_steps=$((steps / 4)) --set steps=$steps --set progress_interval=0 \
        --summary-json "$out/concurrent${n}_round${round}_k$k.json" >/dev/null 2>&1 &
    done
    wait
    echo "contention round $round: $n independent 1-rank runs at once, wall seconds" \
      "$(grep -ho '"wall_seconds": [0-9.e+-]*' "$out"/concurrent${n}_round${round}_k*.json | cut -d' ' -f2 | sort -g | tr '\n' ' ')"
  done
  # One file comes back from the lent machine more surely than dozens.
  tar -czf "$out.tar.gz" -C "$(dirname "$out")" "$(basename "$out")" && rm -rf "$out"
}
export -f scaling_runs
if [ -z "$only" ] || [ "$only" = scaling ]; then
  left=$(( 300 - ($(date +%s) - script_start) ))
  [ -n "$only" ] && left=${SCALING_SECONDS:-120}
  if [ $left -ge 20 ]; then
    part "weak scaling lj-fluid, host back end, n_cells ${SCALING_CELLS:-16} per rank" $left scaling_runs $((left - 5))
  else
    echo "## weak scaling: not run ($left s left of the 5 minutes)"
  fi
fi
echo "# gpu_check.sh: exit $status"
exit $status

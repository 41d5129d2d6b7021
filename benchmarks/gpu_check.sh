#!/usr/bin/env bash
# The one script a lent GPU machine runs (at most 5 minutes on one H100/H200: the parts' limits
# add up to 300 s), from the bundle
# that benchmarks/gpu_bundle.sh packed and tried here:
#   tests       gpu_tests: the execution layer's CUDA reductions, scans and sorts against the
#               host's, the GPU pair fluid against an all-pairs reference, its energy drift
#   sanitizer   compute-sanitizer memcheck and racecheck on the execution-layer tests and a
#               tiny pair-fluid run (said so where the machine has no sanitizer or refuses it)
#   throughput  WCA at rho 0.8, 1 million atoms, double and mixed precision (the figure the
#               engine must keep: 3.7e9 atom-steps/s on an H100)
# usage: bash benchmarks/gpu_check.sh [--only PART] [--bundle DIR]
# The log goes to $OUT/gpu_check.log where the device tool sets OUT (copy it to
# benchmarks/logs/), else to benchmarks/logs/gpu_check_<date>.log. Each part has its own time
# limit; the exit status is that of the first part that failed (124: it ran out of time).
set -uo pipefail
cd "$(dirname "$0")/.."
only="" bundle=gpu_bundle
while [ $# -gt 0 ]; do
  case $1 in
    --only) only=${2:?--only needs tests, sanitizer or throughput}; shift 2 ;;
    --bundle) bundle=${2:?--bundle needs a directory}; shift 2 ;;
    *) echo "gpu_check.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
case $only in ""|tests|sanitizer|throughput) ;; *) echo "gpu_check.sh: no part '$only'" >&2; exit 2 ;; esac
[ -x "$bundle/bin/gpu_tests" ] || { echo "gpu_check.sh: no bundle at $bundle (benchmarks/gpu_bundle.sh)" >&2; exit 2; }
# A bundle from other code than this tree's would measure the wrong thing.
packed=$(sed -n 's/^commit //p' "$bundle/MANIFEST" | cut -d' ' -f1)
here=$(git rev-parse --short=12 HEAD 2>/dev/null || true)
if [ -n "$here" ] && [ "$packed" != "$here" ]; then
  echo "gpu_check.sh: the bundle is from $packed, this tree is $here: run benchmarks/gpu_bundle.sh again" >&2
  exit 2
fi
bundle=$(realpath "$bundle")
export LD_LIBRARY_PATH="$bundle/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
bin=$bundle/bin
log=${OUT:+$OUT/gpu_check.log}
log=${log:-benchmarks/logs/gpu_check_$(date -u +%Y-%m-%d).log}
mkdir -p "$(dirname "$log")"
exec > >(tee "$log") 2>&1

echo "# gpu_check.sh ${only:-all parts}; $(date -u +%FT%TZ)"
sed 's/^/# bundle: /' "$bundle/MANIFEST" | head -n 3
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
  part "gpu tests" 120 device_tests
fi

if [ -z "$only" ] || [ "$only" = sanitizer ]; then
  sanitizer=$(command -v compute-sanitizer || ls /usr/local/cuda/bin/compute-sanitizer 2>/dev/null || true)
  if [ -z "$sanitizer" ]; then
    echo "## sanitizer: compute-sanitizer is not on this machine; not run"
  else
    # The small cases only (tens of thousands of particles): the sanitizer slows kernels 10-100x.
    for tool in memcheck racecheck; do
      part "sanitizer $tool" 45 "$sanitizer" --tool "$tool" --error-exitcode 99 \
        "$bin/gpu_tests" --gtest_brief=1 --gtest_filter='DeviceFunctors.*:GpuPath.StopsWithAClearMessageWhenTheRunBlowsUp'
    done
  fi
fi

if [ -z "$only" ] || [ "$only" = throughput ]; then
  for precision in double mixed; do
    part "throughput WCA 1M $precision" 45 "$bin/emergent-gpu-bench" --cells 63 --density 0.8 \
      --skin 0.3 --steps 500 --warmup 500 --repeats 3 --precision "$precision"
  done
fi
echo "# gpu_check.sh: exit $status"
exit $status

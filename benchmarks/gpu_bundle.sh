#!/usr/bin/env bash
# Packs what benchmarks/gpu_check.sh runs on a lent GPU machine, which is a bare CUDA image (no
# Open MPI, HDF5, Boost, no package registry; at most 64 MiB travels): the GPU programs built
# here (CUDA linked statically) and the shared libraries they load beyond the C library, then
# tries each here in a clean environment, so a missing library shows here, not on the device.
# usage: benchmarks/gpu_bundle.sh [DIR]   (default gpu_bundle/, ignored by git: pass it to the
#        device tool's `carry`, then run `bash benchmarks/gpu_check.sh` there)
# Exit: 0 packed and tried; 1 too large or a program does not start; 2 not built.
set -euo pipefail
cd "$(dirname "$0")/.."
dir=$(realpath -m "${1:-gpu_bundle}")
build=${BUILD_DIR:-build}
limit_mib=50
programs=(gpu_tests emergent-gpu-bench)
for p in "${programs[@]}"; do
  [ -x "$build/bin/$p" ] || { echo "gpu_bundle.sh: $build/bin/$p not built (bash scripts/build, with nvcc)" >&2; exit 2; }
done
grep -q "CudaExecution" "$build/bin/gpu_tests" ||
  { echo "gpu_bundle.sh: $build was configured without CUDA (its gpu_tests have no device tests)" >&2; exit 2; }
rm -rf "$dir"
mkdir -p "$dir/bin" "$dir/lib"
for p in "${programs[@]}"; do
  cp "$build/bin/$p" "$dir/bin/"
  # Every library the loader finds for it, except the C library's own (present on any glibc
  # machine, and bound to its kernel interface).
  ldd "$build/bin/$p" | awk '/=> \// {print $3}' | while read -r lib; do
    case $(basename "$lib") in
      libc.so*|libm.so*|libpthread.so*|libdl.so*|librt.so*|ld-linux*) ;;
      *) [ -e "$dir/lib/$(basename "$lib")" ] || cp -L "$lib" "$dir/lib/" ;;
    esac
  done
done
{
  echo "commit $(git rev-parse --short=12 HEAD)$(git diff --quiet HEAD -- src include tests benchmarks || echo ' (with uncommitted changes)')"
  echo "built $(date -u +%FT%TZ) on $(lscpu | sed -n 's/^Model name: *//p' | head -n 1)"
  echo "nvcc $(/usr/local/cuda/bin/nvcc --version 2>/dev/null | sed -n 's/.*release \([0-9.]*\).*/\1/p')," \
       "CUDA flags '$(sed -n 's/^CMAKE_CUDA_FLAGS_RELEASE:[A-Z]*=//p' "$build/CMakeCache.txt")'"
  # The newest C library version the programs and libraries ask for: the device's must be
  # at least this (Debian 12 builds need glibc 2.36).
  echo "needs glibc $(objdump -T "$dir"/bin/* "$dir"/lib/* 2>/dev/null | grep -o 'GLIBC_[0-9.]*' |
                      sed 's/GLIBC_//' | sort -V | tail -n 1)"
  (cd "$dir" && find bin lib -type f -printf '%P %s\n' | sort)
} >"$dir/MANIFEST"
size=$(du -sm "$dir" | cut -f1)
if [ "$size" -gt "$limit_mib" ]; then
  echo "gpu_bundle.sh: $dir is $size MiB, over the $limit_mib MiB that may travel" >&2
  exit 1
fi
# Tried in a clean environment: only the bundle's libraries and the C library. Without a device
# the GPU tests report themselves skipped; what matters here is that everything loads and runs.
status=0
if ! env -i PATH=/usr/bin:/bin LD_LIBRARY_PATH="$dir/lib" "$dir/bin/gpu_tests" --gtest_brief=1 \
     >"$dir/try.log" 2>&1; then
  echo "gpu_bundle.sh: gpu_tests from the bundle failed here (see $dir/try.log)" >&2
  status=1
fi
# The benchmark's option check comes before any device: it answers bad input anywhere.
answer=$(env -i PATH=/usr/bin:/bin LD_LIBRARY_PATH="$dir/lib" "$dir/bin/emergent-gpu-bench" \
         --cells x 2>&1 || true)
if ! grep -q "is not a number" <<<"$answer"; then
  echo "gpu_bundle.sh: emergent-gpu-bench from the bundle does not start" >&2
  status=1
fi
[ $status -eq 0 ] && echo "gpu_bundle.sh: $dir ($size MiB) packed and tried: carry it and run bash benchmarks/gpu_check.sh"
exit $status

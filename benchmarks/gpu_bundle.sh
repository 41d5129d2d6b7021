#!/usr/bin/env bash
# Packs what benchmarks/gpu_check.sh runs on a lent GPU machine, which is a bare CUDA image (no
# Open MPI, HDF5, Boost, no package registry; at most 64 MiB travels): the programs built here
# (CUDA linked statically: the engine `emergent`, gpu_tests, the pair-fluid benchmark), Open
# MPI's launcher with its components and PMIx (for 2 ranks on one GPU) under usr/, relocated
# with OPAL_PREFIX, and every shared library all of these load beyond the C library; then
# tries each here in a clean environment (a scene on 2 ranks through the bundle's mpirun,
# checked with strace to open no Open MPI file outside the bundle), so a missing piece shows
# here, not on the device. bundle_env.sh in it sets the environment.
# usage: benchmarks/gpu_bundle.sh [DIR]   (default gpu_bundle/; it writes DIR.tar.xz, ignored by
#        git: pass gpu_bundle.tar.xz to the device tool's `carry`, then run
#        `bash benchmarks/gpu_check.sh` there, which unpacks it)
#        REFERENCE=1 adds the throughput reference: emergent-gpu-bench, the separate periodic
#        pair system that the engine replaced (3.7e9 atom-steps/s on an H100), built from the
#        last commit that had it into build-reference/, so gpu_check.sh measures the engine
#        beside it on the same device.
# Exit: 0 packed and tried; 1 too large (the bundle, or with the tree and ../shared over 64 MiB)
#       or a program does not start; 2 not built.
set -euo pipefail
cd "$(dirname "$0")/.."
dir=$(realpath -m "${1:-gpu_bundle}")
build=${BUILD_DIR:-build}
limit_mib=50   # the bundle alone
travel_mib=64  # bundle, working tree and ../shared together (the device tool's limit)
programs=(gpu_tests emergent)
reference_commit=d91cbba24cdb  # the last commit with src/gpu/periodic_pair_system.cu
multi=/usr/lib/x86_64-linux-gnu  # Debian's Open MPI and PMIx live below it
for p in "${programs[@]}"; do
  [ -x "$build/bin/$p" ] || { echo "gpu_bundle.sh: $build/bin/$p not built (bash scripts/build, with nvcc)" >&2; exit 2; }
done
grep -q "CudaExecution" "$build/bin/gpu_tests" ||
  { echo "gpu_bundle.sh: $build was configured without CUDA (its gpu_tests have no device tests)" >&2; exit 2; }
if [ -n "${REFERENCE:-}" ] && [ ! -x build-reference/bin/emergent-gpu-bench ]; then
  ref_tree=$(mktemp -d)
  git worktree add -f --detach "$ref_tree" "$reference_commit" >/dev/null 2>&1 &&
  cmake -S "$ref_tree" -B build-reference -DCMAKE_BUILD_TYPE=Release >build-reference.log 2>&1 &&
  cmake --build build-reference -j"$(nproc)" --target emergent-gpu-bench >>build-reference.log 2>&1 ||
    { echo "gpu_bundle.sh: the reference benchmark did not build (build-reference.log)" >&2; exit 2; }
  git worktree remove --force "$ref_tree"
fi
rm -rf "$dir"
mkdir -p "$dir/bin" "$dir/lib" "$dir/usr/bin" "$dir/usr/lib/x86_64-linux-gnu" "$dir/usr/share"
# Every library the loader finds for a program or component, except the C library's own
# (present on any glibc machine, and bound to its kernel interface).
libraries_of() {
  ldd "$1" 2>/dev/null | awk '/=> \// {print $3}' | while read -r lib; do
    case $(basename "$lib") in
      libc.so*|libm.so*|libpthread.so*|libdl.so*|librt.so*|ld-linux*) ;;
      *) [ -e "$dir/lib/$(basename "$lib")" ] || cp -L "$lib" "$dir/lib/" ;;
    esac
  done
}
for p in "${programs[@]}"; do
  cp "$build/bin/$p" "$dir/bin/"
  libraries_of "$build/bin/$p"
done
if [ -n "${REFERENCE:-}" ]; then
  cp build-reference/bin/emergent-gpu-bench "$dir/bin/"
  libraries_of build-reference/bin/emergent-gpu-bench
fi
# Open MPI for 2 ranks: its launcher and daemon, its component and help files, PMIx's.
cp /usr/bin/orterun "$dir/usr/bin/mpirun"
cp /usr/bin/orted "$dir/usr/bin/"
cp -a $multi/openmpi $multi/pmix2 "$dir/usr/lib/x86_64-linux-gnu/"
rm -rf "$dir/usr/lib/x86_64-linux-gnu/openmpi/include" "$dir/usr/lib/x86_64-linux-gnu/pmix2/include"
cp -a /usr/share/openmpi "$dir/usr/share/"
for f in "$dir"/usr/bin/* $(find "$dir/usr/lib" -name '*.so*' -type f); do libraries_of "$f"; done
cat >"$dir/bundle_env.sh" <<'ENV'
# Source this: the bundle's libraries and its relocated Open MPI (Debian's, moved under usr/).
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
export LD_LIBRARY_PATH="$here/lib:$here/usr/lib/x86_64-linux-gnu/openmpi/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export PATH="$here/bin:$here/usr/bin:$PATH"
export OPAL_PREFIX="$here/usr" PMIX_PREFIX="$here/usr/lib/x86_64-linux-gnu/pmix2"
export PMIX_MCA_mca_base_component_path="$here/usr/lib/x86_64-linux-gnu/pmix2/lib/pmix"
# hwloc's optional plugins (X11, OpenCL, PCI) are not bundled: none are loaded.
export HWLOC_PLUGINS_PATH="$here/usr/lib/x86_64-linux-gnu/hwloc"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# PMIx's zlib compression component does not load from the bundle (a symbol of the system's
# PMIx build); PMIx works without it. Its load error and warning are kept out of the logs.
export PMIX_MCA_mca_base_component_show_load_errors=0 PMIX_MCA_pcompress_base_silence_warning=1
ENV
{
  echo "commit $(git rev-parse --short=12 HEAD)$(git diff --quiet HEAD -- src include tests benchmarks || echo ' (with uncommitted changes)')"
  echo "built $(date -u +%FT%TZ) on $(lscpu | sed -n 's/^Model name: *//p' | head -n 1)"
  echo "nvcc $(/usr/local/cuda/bin/nvcc --version 2>/dev/null | sed -n 's/.*release \([0-9.]*\).*/\1/p')," \
       "CUDA flags '$(sed -n 's/^CMAKE_CUDA_FLAGS_RELEASE:[A-Z]*=//p' "$build/CMakeCache.txt")'"
  # The newest C library version the programs and libraries ask for: the device's must be
  # at least this (Debian 12 builds need glibc 2.36).
  echo "needs glibc $(objdump -T "$dir"/bin/* "$dir"/lib/* 2>/dev/null | grep -o 'GLIBC_[0-9.]*' |
                      sed 's/GLIBC_//' | sort -V | tail -n 1)"
  (cd "$dir" && find bin lib usr -type f -printf '%P %s\n' | sort)
} >"$dir/MANIFEST"
# Tried in a clean environment: only the bundle's libraries and the C library. Without a device
# the GPU tests report themselves skipped; what matters here is that everything loads and runs.
status=0
if ! env -i PATH=/usr/bin:/bin HOME="$dir" bash -c "source '$dir/bundle_env.sh' && gpu_tests --gtest_brief=1" \
     >"$dir/try.log" 2>&1; then
  echo "gpu_bundle.sh: gpu_tests from the bundle failed here (see $dir/try.log)" >&2
  status=1
fi
# The engine on 2 ranks through the bundle's own mpirun, in a clean environment, traced: no
# program or shared library may come from outside the bundle (the device has none). Where this
# machine allows a private mount namespace, its own Open MPI, PMIx and hwloc plugin folders are
# hidden too (PMIx scans its built-in component folder besides the one it is given); without
# one, files in those folders are let through. Optional configuration files (/etc/openmpi,
# PMIx's defaults) are read where present, absent there.
try=$(mktemp -d)
trap '[ -n "${KEEP_TRY:-}" ] || rm -rf "$try"' EXIT
mkdir "$try/empty"
hidden=($multi/openmpi $multi/pmix2 $multi/hwloc /usr/share/openmpi)
run_2_ranks="source '$dir/bundle_env.sh' &&
  strace -f -qq -o '$try/trace' -e trace=openat,execve mpirun -q --oversubscribe -np 2 \
    emergent run lj-fluid --preset tiny --set steps=40 --set equilibration_steps=20 \
    --set backend=host -o '$try/run'"
isolated=yes
if unshare -m true 2>/dev/null; then
  hide=""
  for h in "${hidden[@]}"; do [ -d "$h" ] && hide+="mount --bind '$try/empty' '$h' && "; done
  env -i PATH=/usr/bin:/bin HOME="$try" unshare -m bash -c "$hide $run_2_ranks" >"$dir/try_mpi.log" 2>&1
else
  isolated=no
  env -i PATH=/usr/bin:/bin HOME="$try" bash -c "$run_2_ranks" >"$dir/try_mpi.log" 2>&1
fi
if [ $? -ne 0 ]; then
  echo "gpu_bundle.sh: emergent on 2 ranks from the bundle failed here (see $dir/try_mpi.log)" >&2
  status=1
fi
let_through='^$'
[ $isolated = no ] && let_through="^($(IFS='|'; echo "${hidden[*]}"))/"
outside=$(grep -v ENOENT "$try/trace" 2>/dev/null | grep -oE '"/[^"]*"' | tr -d '"' | grep -v "^$dir/" |
          grep -E '\.so(\.[0-9.]+)?$|/orted$|/mpirun$' | grep -vE "$let_through" |
          grep -vE '/(libc|libm|libpthread|libdl|librt)\.so|/ld-linux|^/etc/ld\.so' | sort -u || true)
if [ -n "$outside" ]; then
  echo "gpu_bundle.sh: the bundle's run opened files outside it: $(echo $outside)" >&2
  status=1
fi
echo "gpu_bundle.sh: 2 ranks from the bundle ran here (isolated from this machine's Open MPI: $isolated)"
[ $status -eq 0 ] || exit $status
# What travels is one compressed file (the libraries shrink about fourfold), beside the working
# tree git does not ignore and ../shared: the three together may not pass 64 MiB, or the device
# refuses the run before it starts.
archive="$dir.tar.xz"
tar -cf - -C "$(dirname "$dir")" "$(basename "$dir")" | xz -T0 -6 >"$archive"
mib() { echo $(( ($1 + 1048575) / 1048576 )); }
archive_bytes=$(stat -c %s "$archive")
tree_bytes=$(git ls-files -z --cached --others --exclude-standard | du -cb --files0-from=- 2>/dev/null | tail -n 1 | cut -f1)
shared_bytes=$( [ -d ../shared ] && du -sb ../shared | cut -f1 || echo 0)
total=$(( archive_bytes + tree_bytes + shared_bytes ))
if [ "$(mib "$archive_bytes")" -gt "$limit_mib" ] || [ "$total" -gt $(( travel_mib * 1048576 )) ]; then
  echo "gpu_bundle.sh: what would travel is $(mib "$total") MiB (bundle $(mib "$archive_bytes")," \
       "tree $(mib "$tree_bytes"), ../shared $(mib "$shared_bytes")), over the $travel_mib MiB" \
       "the device takes (the bundle alone may have $limit_mib)" >&2
  exit 1
fi
echo "gpu_bundle.sh: $archive ($(mib "$archive_bytes") MiB; $(du -sm "$dir" | cut -f1) MiB unpacked) packed and" \
     "tried; with the tree and ../shared $(mib "$total") of $travel_mib MiB: carry it and run bash benchmarks/gpu_check.sh"

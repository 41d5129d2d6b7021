// SPDX-License-Identifier: MIT
// The thin execution layer: runs a per-particle functor as a CPU loop (here) or a CUDA grid
// (emergent/cuda_launch.cuh), and does the reductions, scans and sorts around them (here the
// standard library's way, on CUDA CUB's; emergent/cuda_algorithms.cuh). Physics lives in the
// functors, never in the launchers. Each primitive has the same meaning on both back ends;
// what may differ is only the order of floating-point additions (stated per primitive).
//
// exec::Target picks the back end at run time (the run parameter `backend`). A source file
// that launches through a Target is compiled as CUDA in a CUDA build, so that its loops can
// run on the device; compiled as plain C++ (a build without CUDA, or a plugin built with a C++
// compiler) a launch on the device is refused with a clear error.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "emergent/macros.hpp"

namespace emergent::exec {

/// Two per-particle functors fused into one pass: second(i) runs right after first(i), so it
/// reads what first just wrote from cache rather than from memory, and its result is the
/// pass's: a stage then a measure of the particle it leaves, reduced in the same pass
/// (transform_sum, transform_max, which call it once for every particle), e.g. a drift and the
/// displacement since the list was built. Only for functors that touch particle i's data alone.
template <class First, class Second>
struct Then {
    First first;
    Second second;
    EMERGENT_HD auto operator()(std::size_t i) const {
        first(i);
        return second(i);
    }
};

/// a[i] as a double: sums an array through transform_sum.
template <class T>
struct ElementOf {
    const T* a;
    EMERGENT_HD double operator()(std::size_t i) const { return static_cast<double>(a[i]); }
};

/// Host<->device traffic of this process, counted by the back ends: whole arrays (particle
/// data, lists) apart from scalars (a reduction's result, a flag: each a read-back the host
/// waits for), so a test can assert that a step moves no array. The host back end moves
/// nothing. With them the work a step is made of: passes over particles (the loops launched
/// through a Target, kernel launches on a device; a sort counts as one) and collective
/// operations across ranks (decomp's reductions and the engine's own), the step ledger's counts
/// (Simulation::step_ledger).
struct Transfers {
    std::uint64_t arrays = 0, array_bytes = 0;
    std::uint64_t scalars = 0, scalar_bytes = 0;
    std::uint64_t passes = 0, collectives = 0;
};
inline Transfers& transfers() {
    static Transfers counts;
    return counts;
}
/// Counts a result of `bytes` the host read back from a back end's memory.
inline void count_scalar(std::size_t bytes) {
    transfers().scalars += 1;
    transfers().scalar_bytes += bytes;
}

/// Counts a collective operation across ranks (every rank counts its own call).
inline void count_collective() { transfers().collectives += 1; }

/// Host back end: plain loops the compiler can vectorise.
struct Host {};

template <class Functor>
void for_each(Host, std::size_t n, const Functor& f) {
    for (std::size_t i = 0; i < n; ++i) f(i);
}

/// Sum of f(i) over i < n. Host: added in index order, so bitwise the plain loop's result and
/// the same run to run. CUDA: a tree order, the same run to run on one device. T: T{} and +=.
template <class T, class F>
T transform_sum(Host, std::size_t n, const F& f) {
    T sum{};
    for (std::size_t i = 0; i < n; ++i) sum += f(i);
    return sum;
}

/// init + the sum of f(i) over the i < n where pred(i) holds: for work on the few particles a
/// cheap test picks out (those crossing a wall). Host: added to init in index order, so bitwise
/// a running total kept by a plain loop. CUDA: a tree order, then added to init.
template <class T, class Pred, class F>
T transform_sum_if(Host, std::size_t n, T init, const Pred& pred, const F& f) {
    for (std::size_t i = 0; i < n; ++i)
        if (pred(i)) init += f(i);
    return init;
}

/// The larger of a and b, where a NaN wins: a guard taking a maximum must see it.
template <class T>
EMERGENT_HD EMERGENT_INLINE T max_keeping_nan(const T& a, const T& b) {
    if (a != a) return a;
    if (b != b) return b;
    return a < b ? b : a;
}

/// The largest of init and f(i) over i < n; a NaN anywhere is the result (max_keeping_nan).
/// Exact on both back ends (a maximum does not depend on the order). f(i) is called once for
/// every i, a NaN or not, so f may also act on particle i (exec::Then).
template <class T, class F>
T transform_max(Host, std::size_t n, T init, const F& f) {
    T best = init;
    for (std::size_t i = 0; i < n; ++i) best = max_keeping_nan(best, f(i));
    return best;
}

/// The smallest i < n with pred(i) true, or n if there is none (a guard's first offender:
/// the same particle on both back ends).
template <class Pred>
std::size_t first_index(Host, std::size_t n, const Pred& pred) {
    for (std::size_t i = 0; i < n; ++i)
        if (pred(i)) return i;
    return n;
}

/// out[i] = in[0] + ... + in[i-1] for i < n; returns the total of all n. in and out may be the
/// same array. Integers: exact on both back ends.
template <class T>
T exclusive_scan(Host, const T* in, T* out, std::size_t n) {
    T running{};
    for (std::size_t i = 0; i < n; ++i) {
        const T v = in[i];
        out[i] = running;
        running += v;
    }
    return running;
}

/// The same scan with no total coming back: the host does not wait for it (on a device it is
/// queued like a loop), for a scan whose total the host knows already or reads later with
/// other results. in and out may be the same array.
template <class T>
void exclusive_scan_queued(Host, const T* in, T* out, std::size_t n) {
    exclusive_scan(Host{}, in, out, n);
}

/// Sorts the pairs (keys[i], values[i]) by key, stably (equal keys keep their order), in
/// place; keys must be below 2^key_bits (fewer bits, fewer radix passes on CUDA). Both back ends
/// give the same order. Keys of 32 or 64 bits (a cell and an id in one key: one sort, not two).
template <class Key>
void sort_pairs(Host, Key* keys, std::uint32_t* values, std::size_t n, int key_bits = 8 * sizeof(Key)) {
    static_assert(std::is_same_v<Key, std::uint32_t> || std::is_same_v<Key, std::uint64_t>,
                  "sort_pairs: 32- or 64-bit unsigned keys");
    // Keys beyond key_bits would sort differently on CUDA (its radix passes ignore those bits).
    if (key_bits < static_cast<int>(8 * sizeof(Key)))
        for (std::size_t i = 0; i < n; ++i)
            if (keys[i] >> key_bits)
                throw std::invalid_argument("sort_pairs: a key has more than key_bits bits");
    std::vector<std::uint32_t> order(n);
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return keys[a] < keys[b]; });
    std::vector<Key> k(n);
    std::vector<std::uint32_t> v(n);
    for (std::size_t i = 0; i < n; ++i) {
        k[i] = keys[order[i]];
        v[i] = values[order[i]];
    }
    std::copy(k.begin(), k.end(), keys);
    std::copy(v.begin(), v.end(), values);
}


/// Where the loops of a run go, chosen at run time: the host's loops on the store (host), on
/// separate host memory (checking), or CUDA kernels on the device's memory (cuda).
struct Target {
    bool device = false;    ///< CUDA kernels; else host loops
    bool separate = false;  ///< the arrays are not the host's: a result read back is a transfer
    void* stream = nullptr; ///< the CUDA stream (cudaStream_t) of a device target
    /// MPI reads and writes the target's memory: messages go without staging through the host
    /// (a CUDA-aware MPI; on the checking back end, its separate memory as a test of the path).
    bool direct_mpi = false;
};

/// Throws: a loop compiled without CUDA was asked to run on the device.
[[noreturn]] void refuse_device_loop(const char* what);
/// Copies `bytes` from the target's memory to the host (a plain copy on the host back ends);
/// counted as a scalar transfer where the target's memory is separate.
void read_from(const Target& target, void* to, const void* from, std::size_t bytes);

/// Waits until the target's queued loops have finished (host targets: nothing to wait for).
void synchronize(const Target& target);

/// One value of an array in the target's memory, read by the host (a guard's offender).
template <class T>
T read_one(const Target& target, const T* at) {
    T value;
    read_from(target, &value, at, sizeof(T));
    return value;
}

}  // namespace emergent::exec

#if defined(__CUDACC__)
#include "emergent/cuda_algorithms.cuh"
#endif

namespace emergent::exec {

// The run-time dispatch. Its mangled names differ between CUDA and plain C++ compilation
// (inline namespaces), so the two forms never stand in for each other at link time.
#if defined(__CUDACC__)
inline namespace with_cuda {
inline Cuda on_device(const Target& target) { return Cuda{static_cast<cudaStream_t>(target.stream)}; }
#define EMERGENT_ON_DEVICE(name, ...) \
    if (target.device) return name(on_device(target), __VA_ARGS__)
#else
inline namespace host_only {
#define EMERGENT_ON_DEVICE(name, ...) \
    if (target.device) refuse_device_loop(#name)
#endif

/// The host back ends count a reduction's result as the device's copy back is counted, so the
/// checking back end reports the traffic a device run has.
inline void count_result(const Target& target, std::size_t bytes) {
    if (target.separate && !target.device) count_scalar(bytes);
}
/// Every loop launched through a Target, on every back end.
inline void count_pass() { transfers().passes += 1; }

template <class Functor>
void for_each(const Target& target, std::size_t n, const Functor& f) {
    count_pass();
    EMERGENT_ON_DEVICE(for_each, n, f);
    for_each(Host{}, n, f);
}

template <class T, class F>
T transform_sum(const Target& target, std::size_t n, const F& f) {
    count_pass();
    EMERGENT_ON_DEVICE(transform_sum<T>, n, f);
    count_result(target, sizeof(T));
    return transform_sum<T>(Host{}, n, f);
}

template <class T, class Pred, class F>
T transform_sum_if(const Target& target, std::size_t n, T init, const Pred& pred, const F& f) {
    count_pass();
    EMERGENT_ON_DEVICE(transform_sum_if, n, init, pred, f);
    count_result(target, sizeof(T));
    return transform_sum_if(Host{}, n, init, pred, f);
}

template <class T, class F>
T transform_max(const Target& target, std::size_t n, T init, const F& f) {
    count_pass();
    EMERGENT_ON_DEVICE(transform_max, n, init, f);
    count_result(target, sizeof(T));
    return transform_max(Host{}, n, init, f);
}

template <class Pred>
std::size_t first_index(const Target& target, std::size_t n, const Pred& pred) {
    count_pass();
    EMERGENT_ON_DEVICE(first_index, n, pred);
    count_result(target, sizeof(std::size_t));
    return first_index(Host{}, n, pred);
}

/// See the host version; in and out are arrays in the target's memory. The total comes back
/// to the host (a scalar transfer on a separate back end).
template <class T>
T exclusive_scan(const Target& target, const T* in, T* out, std::size_t n) {
    count_pass();
    EMERGENT_ON_DEVICE(exclusive_scan, in, out, n);
    count_result(target, sizeof(T));
    return exclusive_scan(Host{}, in, out, n);
}

/// See the host version: no total comes back (nothing is read back).
template <class T>
void exclusive_scan_queued(const Target& target, const T* in, T* out, std::size_t n) {
    count_pass();
    if (target.device) {
#if defined(__CUDACC__)
        exclusive_scan_queued(on_device(target), in, out, n);
        return;
#else
        refuse_device_loop("exclusive_scan_queued");
#endif
    }
    exclusive_scan_queued(Host{}, in, out, n);
}

/// See the host version; keys and values are arrays in the target's memory.
template <class Key>
void sort_pairs(const Target& target, Key* keys, std::uint32_t* values, std::size_t n,
                int key_bits = 8 * sizeof(Key)) {
    count_pass();
    if (target.device) {
#if defined(__CUDACC__)
        sort_pairs(on_device(target), keys, values, n, key_bits);
        return;
#else
        refuse_device_loop("sort_pairs");
#endif
    }
    sort_pairs(Host{}, keys, values, n, key_bits);
}

#undef EMERGENT_ON_DEVICE
}  // inline namespace

}  // namespace emergent::exec

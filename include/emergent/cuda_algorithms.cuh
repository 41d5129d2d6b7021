// SPDX-License-Identifier: MIT
// CUDA back end of the execution layer's reductions, scans and sorts (CUB), with the meaning
// of their host versions in emergent/execution.hpp. A result the host needs (a sum, a
// maximum, a scan's total) is copied back and counted as a scalar transfer.
#pragma once

#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_reduce.cuh>
#include <cub/device/device_scan.cuh>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/iterator/transform_iterator.h>

#include <climits>
#include <cstdint>
#include <stdexcept>

#include "emergent/execution.hpp"
#include "emergent/cuda_launch.cuh"

namespace emergent::exec {

/// Device memory the CUB calls work in, grown to the largest request and kept: one per
/// process (one GPU per rank).
class CudaScratch {
  public:
    ~CudaScratch() {
        if (data_) cudaFree(data_);
    }
    void* get(std::size_t bytes) {
        if (bytes > bytes_) {
            if (data_) EMERGENT_CUDA_CHECK(cudaFree(data_));
            data_ = nullptr;
            bytes_ = 0;
            EMERGENT_CUDA_CHECK(cudaMalloc(&data_, bytes));
            bytes_ = bytes;
        }
        return data_;
    }
    static CudaScratch& instance() {
        static CudaScratch s;
        return s;
    }

  private:
    void* data_ = nullptr;
    std::size_t bytes_ = 0;
};

namespace cuda_detail {

template <class T, class F>
struct Apply {
    F f;
    EMERGENT_HD T operator()(std::size_t i) const { return f(i); }
};

/// CUB counts items in int.
inline int item_count(std::size_t n) {
    if (n > static_cast<std::size_t>(INT_MAX))
        throw std::length_error("execution layer: more than 2^31 - 1 items in one call");
    return static_cast<int>(n);
}

struct Sum {
    template <class T>
    __device__ T operator()(const T& a, const T& b) const {
        T s = a;
        s += b;
        return s;
    }
};

struct Min {
    template <class T>
    __device__ T operator()(const T& a, const T& b) const { return b < a ? b : a; }
};

/// f(i) where pred(i) holds, else T{}.
template <class T, class Pred, class F>
struct ApplyIf {
    Pred pred;
    F f;
    EMERGENT_HD T operator()(std::size_t i) const { return pred(i) ? f(i) : T{}; }
};

/// i where pred(i) holds, else n: the smallest of these is the first offender.
template <class Pred>
struct IndexIf {
    Pred pred;
    std::size_t n;
    EMERGENT_HD std::size_t operator()(std::size_t i) const { return pred(i) ? i : n; }
};

struct MaxKeepingNan {
    template <class T>
    __device__ T operator()(const T& a, const T& b) const { return max_keeping_nan(a, b); }
};

/// The n_values values at device address `from`, copied to the host and counted.
template <class T>
void read_back(const T* from, T* to, std::size_t n_values, cudaStream_t stream) {
    EMERGENT_CUDA_CHECK(cudaMemcpyAsync(to, from, n_values * sizeof(T), cudaMemcpyDeviceToHost, stream));
    EMERGENT_CUDA_CHECK(cudaStreamSynchronize(stream));
    transfers().scalars += n_values;
    transfers().scalar_bytes += n_values * sizeof(T);
}

/// Reduces f(0..n-1) with op from init into one value on the host.
template <class T, class F, class Op>
T reduce(Cuda backend, std::size_t n, T init, const F& f, Op op) {
    if (n == 0) return init;
    const ProfiledCall profiled("reduce", functor_name<F>());
    const int items = item_count(n);
    auto in = thrust::make_transform_iterator(thrust::counting_iterator<std::size_t>(0),
                                              Apply<T, F>{f});
    // The result goes after the temporary storage, in the same allocation.
    std::size_t temp = 0;
    EMERGENT_CUDA_CHECK(cub::DeviceReduce::Reduce(nullptr, temp, in, static_cast<T*>(nullptr),
                                                  items, op, init, backend.stream));
    const std::size_t offset = (temp + alignof(T) + 15) / 16 * 16;
    char* base = static_cast<char*>(CudaScratch::instance().get(offset + sizeof(T)));
    T* out = reinterpret_cast<T*>(base + offset);
    EMERGENT_CUDA_CHECK(cub::DeviceReduce::Reduce(base, temp, in, out, items, op,
                                                  init, backend.stream));
    T result;
    read_back(out, &result, 1, backend.stream);
    return result;
}

}  // namespace cuda_detail

/// See the host version: the same sum, added in a tree order fixed for a given n and device.
template <class T, class F>
T transform_sum(Cuda backend, std::size_t n, const F& f) {
    return cuda_detail::reduce(backend, n, T{}, f, cuda_detail::Sum{});
}

/// See the host version: the same value on both back ends. f may write to its own particle
/// (exec::Then), as in transform_sum_if below: CUB's single-pass reduce reads each item
/// once.
template <class T, class F>
T transform_max(Cuda backend, std::size_t n, T init, const F& f) {
    return cuda_detail::reduce(backend, n, init, f, cuda_detail::MaxKeepingNan{});
}

/// See the host version: the selected terms in a tree order, then added to init. f may write
/// to its own particle (a wall bounce does): it relies on CUB's reduction reading each input
/// once, which its single-pass reduce does (not a documented promise: the device tests
/// compare the particles' state with the host's after the pass).
template <class T, class Pred, class F>
T transform_sum_if(Cuda backend, std::size_t n, T init, const Pred& pred, const F& f) {
    init += cuda_detail::reduce(backend, n, T{}, cuda_detail::ApplyIf<T, Pred, F>{pred, f},
                                cuda_detail::Sum{});
    return init;
}

/// See the host version.
template <class Pred>
std::size_t first_index(Cuda backend, std::size_t n, const Pred& pred) {
    return cuda_detail::reduce(backend, n, n, cuda_detail::IndexIf<Pred>{pred, n}, cuda_detail::Min{});
}

/// See the host version; in and out are device arrays and may be the same.
template <class T>
T exclusive_scan(Cuda backend, const T* in, T* out, std::size_t n) {
    if (n == 0) return T{};
    const ProfiledCall profiled("scan", functor_name<T>());
    const int items = cuda_detail::item_count(n);
    T last_in;
    // The last input is read before the scan may overwrite it (in == out).
    cuda_detail::read_back(in + n - 1, &last_in, 1, backend.stream);
    std::size_t temp = 0;
    EMERGENT_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(nullptr, temp, in, out, items,
                                                      backend.stream));
    EMERGENT_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(CudaScratch::instance().get(temp), temp, in,
                                                      out, items, backend.stream));
    T last_out;
    cuda_detail::read_back(out + n - 1, &last_out, 1, backend.stream);
    return last_out + last_in;
}

/// See the host version: the scan queued on the stream, nothing read back.
template <class T>
void exclusive_scan_queued(Cuda backend, const T* in, T* out, std::size_t n) {
    if (n == 0) return;
    const ProfiledCall profiled("scan", functor_name<T>());
    const int items = cuda_detail::item_count(n);
    std::size_t temp = 0;
    EMERGENT_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(nullptr, temp, in, out, items,
                                                      backend.stream));
    EMERGENT_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(CudaScratch::instance().get(temp), temp, in,
                                                      out, items, backend.stream));
}

/// See the host version; keys and values are device arrays, sorted in place (a stable LSD
/// radix sort through alternate buffers in the scratch memory). Returns with the copy back
/// still queued on the backend's stream: every later use of the scratch memory must be on that
/// stream (the engine uses one stream per process).
template <class Key>
void sort_pairs(Cuda backend, Key* keys, std::uint32_t* values, std::size_t n,
                int key_bits = 8 * sizeof(Key)) {
    if (n < 2) return;
    const ProfiledCall profiled("sort", functor_name<Key>());
    const int items = cuda_detail::item_count(n);
    const std::size_t key_array = (n * sizeof(Key) + 255) / 256 * 256;
    const std::size_t value_array = (n * sizeof(std::uint32_t) + 255) / 256 * 256;
    std::size_t temp = 0;
    cub::DoubleBuffer<Key> k(keys, nullptr);
    cub::DoubleBuffer<std::uint32_t> v(values, nullptr);
    EMERGENT_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(nullptr, temp, k, v, items, 0,
                                                        key_bits, backend.stream));
    char* base = static_cast<char*>(CudaScratch::instance().get(key_array + value_array + temp));
    k = cub::DoubleBuffer<Key>(keys, reinterpret_cast<Key*>(base));
    v = cub::DoubleBuffer<std::uint32_t>(values, reinterpret_cast<std::uint32_t*>(base + key_array));
    EMERGENT_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(base + key_array + value_array, temp, k, v,
                                                        items, 0, key_bits,
                                                        backend.stream));
    // The sort may end in the alternate buffers: copy back so the caller's arrays hold it.
    if (k.Current() != keys)
        EMERGENT_CUDA_CHECK(cudaMemcpyAsync(keys, k.Current(), n * sizeof(Key),
                                            cudaMemcpyDeviceToDevice, backend.stream));
    if (v.Current() != values)
        EMERGENT_CUDA_CHECK(cudaMemcpyAsync(values, v.Current(), n * sizeof(std::uint32_t),
                                            cudaMemcpyDeviceToDevice, backend.stream));
}

}  // namespace emergent::exec

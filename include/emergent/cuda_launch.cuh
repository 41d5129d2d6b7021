// SPDX-License-Identifier: MIT
// CUDA back end of the execution layer: the same per-particle functors as exec::Host, one
// thread per particle.
#pragma once

#include <cuda_runtime.h>

#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "emergent/device_profile.hpp"
#include "emergent/macros.hpp"

namespace emergent::exec {

/// CUDA back end: functors must be EMERGENT_HD and hold device pointers only.
struct Cuda {
    cudaStream_t stream = nullptr;
    int block_size = 256;
};

/// Throws with the CUDA error text and the place of the call.
inline void cuda_check(cudaError_t status, const char* where) {
    if (status != cudaSuccess)
        throw std::runtime_error(std::string("CUDA error at ") + where + ": " +
                                 cudaGetErrorString(status));
}

#define EMERGENT_CUDA_CHECK(call) ::emergent::exec::cuda_check((call), EMERGENT_HERE)

/// The functor's full type as the compiler spells it (in this function's signature).
template <class Functor>
const char* functor_name() {
    return __PRETTY_FUNCTION__;
}

/// After a launch: its error, or with CUDA_LAUNCH_BLOCKING=1 the kernel's own, named by the
/// functor's type, so a failing loop is found without a debugger.
template <class Functor>
void check_launch() {
    cuda_check(cudaGetLastError(), functor_name<Functor>());
}

/// With EMERGENT_PROFILE set (emergent/device_profile.hpp): the call in its scope timed alone,
/// the device synchronised before and after it. Otherwise nothing.
class ProfiledCall {
public:
    ProfiledCall(const char* what, const char* name) : what_(what), name_(profiling() ? name : nullptr) {
        if (!name_) return;
        cudaDeviceSynchronize();  // errors are sticky: the call's own check reports them
        start_ = profile_clock();
    }
    ~ProfiledCall() {
        if (!name_) return;
        cudaDeviceSynchronize();
        profile_add(what_, name_, profile_clock() - start_);
    }
    ProfiledCall(const ProfiledCall&) = delete;
    ProfiledCall& operator=(const ProfiledCall&) = delete;

private:
    const char* what_;
    const char* name_;
    double start_ = 0;
};

template <class Functor>
__global__ void for_each_kernel(std::size_t n, Functor f) {
    const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
    if (i < n) f(i);
}

template <class Functor>
void for_each(Cuda backend, std::size_t n, const Functor& f) {
    if (n == 0) return;
    const ProfiledCall profiled("loop", functor_name<Functor>());
    const unsigned blocks = static_cast<unsigned>((n + backend.block_size - 1) / backend.block_size);
    for_each_kernel<<<blocks, backend.block_size, 0, backend.stream>>>(n, f);
    check_launch<Functor>();
}

/// v from the lane `offset` above, within segments of Width lanes (any trivially copyable v).
template <int Width, class T>
__device__ T shuffle_down(const T& v, unsigned offset) {
    static_assert(sizeof(T) % sizeof(int) == 0, "shuffled values are whole words");
    int words[sizeof(T) / sizeof(int)];
    memcpy(words, &v, sizeof(T));
#pragma unroll
    for (unsigned w = 0; w < sizeof(T) / sizeof(int); ++w)
        words[w] = __shfl_down_sync(0xffffffffu, words[w], offset, Width);
    T out;
    memcpy(&out, words, sizeof(T));
    return out;
}

template <int Lanes, class Functor>
__global__ void for_each_split_kernel(std::size_t n, Functor f) {
    const std::size_t t = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
    const std::size_t i = t / Lanes;
    const unsigned lane = threadIdx.x % Lanes;
    // Every lane of the warp takes part in the shuffles, so none returns early.
    typename Functor::Partial s{};
    if (i < n) s = f.partial(i, lane, Lanes);
#pragma unroll
    for (unsigned offset = Lanes / 2; offset > 0; offset /= 2) s += shuffle_down<Lanes>(s, offset);
    if (i < n && lane == 0) f.store(i, s);
}

/// Calls f(std::integral_constant<int, L>{}) for the run-time lanes per particle L (2, 4, 8, 16
/// or 32): the one place a lane count becomes a kernel's template argument.
template <class F>
void with_lanes(int lanes, F&& f) {
    switch (lanes) {
        case 2: f(std::integral_constant<int, 2>{}); break;
        case 4: f(std::integral_constant<int, 4>{}); break;
        case 8: f(std::integral_constant<int, 8>{}); break;
        case 16: f(std::integral_constant<int, 16>{}); break;
        case 32: f(std::integral_constant<int, 32>{}); break;
        default: throw std::invalid_argument("lanes per particle must be 1, 2, 4, 8, 16 or 32");
    }
}

/// Blocks of the backend's size for `lanes` threads per particle over n particles.
inline unsigned blocks_for(const Cuda& backend, std::size_t n, int lanes) {
    const std::size_t threads = n * static_cast<std::size_t>(lanes);
    return static_cast<unsigned>((threads + backend.block_size - 1) / backend.block_size);
}

/// For functors whose work for particle i is a sum over its neighbours (partial(i, first,
/// stride) and store(i, sum)): `lanes` threads of a warp share each particle and add their
/// partial sums by shuffles. More threads in flight when particles are few or neighbours many.
template <class Functor>
void for_each_split(Cuda backend, std::size_t n, int lanes, const Functor& f) {
    if (lanes == 1) return for_each(backend, n, f);
    if (n == 0) return;
    const ProfiledCall profiled("lanes", functor_name<Functor>());
    with_lanes(lanes, [&](auto width) {
        for_each_split_kernel<decltype(width)::value>
            <<<blocks_for(backend, n, lanes), backend.block_size, 0, backend.stream>>>(n, f);
    });
    check_launch<Functor>();
}

}  // namespace emergent::exec

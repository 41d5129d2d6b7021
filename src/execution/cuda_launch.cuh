// SPDX-License-Identifier: MIT
// CUDA back end of the execution layer: the same per-particle functors as exec::Host, one
// thread per particle.
#pragma once

#include <cuda_runtime.h>

#include <cstddef>
#include <stdexcept>
#include <string>

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

template <class Functor>
__global__ void for_each_kernel(std::size_t n, Functor f) {
    const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
    if (i < n) f(i);
}

template <class Functor>
void for_each(Cuda backend, std::size_t n, const Functor& f) {
    if (n == 0) return;
    const unsigned blocks = static_cast<unsigned>((n + backend.block_size - 1) / backend.block_size);
    for_each_kernel<<<blocks, backend.block_size, 0, backend.stream>>>(n, f);
    EMERGENT_CUDA_CHECK(cudaGetLastError());
}

}  // namespace emergent::exec

// SPDX-License-Identifier: MIT
// Test data to and from the device, for the GPU tests that compare device with host results.
#pragma once

#include <vector>

#include "gpu/device_buffer.cuh"

namespace emergent::fixtures {

template <class T>
gpu::DeviceBuffer<T> on_device(const std::vector<T>& v) {
    gpu::DeviceBuffer<T> d(v.size());
    EMERGENT_CUDA_CHECK(cudaMemcpy(d.data(), v.data(), v.size() * sizeof(T), cudaMemcpyHostToDevice));
    return d;
}

template <class T>
std::vector<T> on_host(const gpu::DeviceBuffer<T>& d) {
    std::vector<T> v(d.size());
    EMERGENT_CUDA_CHECK(cudaMemcpy(v.data(), d.data(), d.bytes(), cudaMemcpyDeviceToHost));
    return v;
}

}  // namespace emergent::fixtures

// SPDX-License-Identifier: MIT
// Owning arrays in device memory and in pinned host memory; every CUDA call checked.
#pragma once

#include <cuda_runtime.h>

#include <cstddef>
#include <utility>

#include "emergent/cuda_launch.cuh"

namespace emergent::gpu {

/// n elements of T in device memory; resize discards the contents.
template <class T>
class DeviceBuffer {
  public:
    DeviceBuffer() = default;
    explicit DeviceBuffer(std::size_t n) { resize(n); }
    ~DeviceBuffer() { release(); }
    DeviceBuffer(const DeviceBuffer&) = delete;
    DeviceBuffer& operator=(const DeviceBuffer&) = delete;
    DeviceBuffer(DeviceBuffer&& o) noexcept { swap(o); }
    DeviceBuffer& operator=(DeviceBuffer&& o) noexcept { swap(o); return *this; }

    void resize(std::size_t n) {
        if (n == size_) return;
        release();
        if (n > 0) EMERGENT_CUDA_CHECK(cudaMalloc(reinterpret_cast<void**>(&data_), n * sizeof(T)));
        size_ = n;
    }
    void swap(DeviceBuffer& o) noexcept {
        std::swap(data_, o.data_);
        std::swap(size_, o.size_);
    }
    T* data() { return data_; }
    const T* data() const { return data_; }
    std::size_t size() const { return size_; }
    std::size_t bytes() const { return size_ * sizeof(T); }

  private:
    void release() {
        if (data_) cudaFree(data_);  // no check: called from the destructor too
        data_ = nullptr;
        size_ = 0;
    }
    T* data_ = nullptr;
    std::size_t size_ = 0;
};

/// One value in pinned host memory, the target of an asynchronous device-to-host copy.
template <class T>
class PinnedValue {
  public:
    PinnedValue() { EMERGENT_CUDA_CHECK(cudaMallocHost(reinterpret_cast<void**>(&p_), sizeof(T))); *p_ = T{}; }
    ~PinnedValue() { cudaFreeHost(p_); }
    PinnedValue(const PinnedValue&) = delete;
    PinnedValue& operator=(const PinnedValue&) = delete;
    T* get() { return p_; }
    T value() const { return *p_; }

  private:
    T* p_ = nullptr;
};

}  // namespace emergent::gpu

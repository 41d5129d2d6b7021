// SPDX-License-Identifier: MIT
// The CUDA device's memory for the particle mirror.
#include "emergent/cuda_launch.cuh"
#include "execution/array_memory.hpp"
#include "emergent/gpu.hpp"

namespace emergent::exec {

namespace {

class CudaDeviceMemory final : public ArrayMemory {
public:
    void* allocate(std::size_t bytes) override {
        void* p = nullptr;
        EMERGENT_CUDA_CHECK(cudaMalloc(&p, bytes > 0 ? bytes : 1));
        return p;
    }
    void release(void* p) noexcept override {
        if (p) cudaFree(p);  // no check: called from destructors too
    }
    void* allocate_staging(std::size_t bytes) override {
        void* p = nullptr;
        EMERGENT_CUDA_CHECK(cudaMallocHost(&p, bytes > 0 ? bytes : 1));
        return p;
    }
    void release_staging(void* p) noexcept override {
        if (p) cudaFreeHost(p);
    }
    void to_backend(void* to, const void* from, std::size_t bytes) override {
        const ProfiledCall profiled("copy", "to the device");
        EMERGENT_CUDA_CHECK(cudaMemcpy(to, from, bytes, cudaMemcpyHostToDevice));
    }
    void to_host(void* to, const void* from, std::size_t bytes) override {
        const ProfiledCall profiled("copy", "to the host");
        EMERGENT_CUDA_CHECK(cudaMemcpy(to, from, bytes, cudaMemcpyDeviceToHost));
    }
    void within(void* to, const void* from, std::size_t bytes) override {
        const ProfiledCall profiled("copy", "within the device");
        EMERGENT_CUDA_CHECK(cudaMemcpy(to, from, bytes, cudaMemcpyDeviceToDevice));
    }
    const char* name() const override { return "CUDA device"; }
};

}  // namespace

std::unique_ptr<ArrayMemory> cuda_device_memory() {
    gpu::select_device();  // throws, in one line, where there is none
    return std::make_unique<CudaDeviceMemory>();
}

}  // namespace emergent::exec

// SPDX-License-Identifier: MIT
// One GPU per rank, chosen by the rank's index on its node.
#include <cuda_runtime.h>

#include <algorithm>
#include <cstdlib>
#include <vector>
#include <stdexcept>
#include <string>

#include "emergent/gpu.hpp"
#include "emergent/cuda_launch.cuh"
#include "gpu/device_memory_use.hpp"

namespace emergent::gpu {

namespace {

/// The rank's index among the ranks of its node, from the launcher's environment (no MPI call:
/// the device must be chosen before any CUDA-aware MPI initialisation touches one).
int local_rank() {
    for (const char* name : {"OMPI_COMM_WORLD_LOCAL_RANK", "SLURM_LOCALID", "MPI_LOCALRANKID",
                             "MV2_COMM_WORLD_LOCAL_RANK", "PMI_LOCAL_RANK"})
        if (const char* v = std::getenv(name)) return std::atoi(v);
    return 0;
}

int device_count() {
    int n = 0;
    const cudaError_t status = cudaGetDeviceCount(&n);
    if (status == cudaSuccess) return n;
    cudaGetLastError();  // clear the sticky error for later calls
    // No device, or no driver (a machine that compiles CUDA but has no GPU): none present.
    // Anything else is a broken set-up that must not read as "no GPU here".
    if (status == cudaErrorNoDevice || status == cudaErrorInsufficientDriver) return 0;
    throw std::runtime_error(std::string("CUDA cannot count devices: ") + cudaGetErrorString(status));
}

std::size_t memory_at_selection = 0;
bool selected = false;

}  // namespace

bool device_present() { return device_count() > 0; }

DeviceInfo select_device() {
    const int n = device_count();
    if (n == 0)
        throw std::runtime_error("execution on the GPU was requested but no CUDA device is present");
    DeviceInfo info;
    info.index = local_rank() % n;
    EMERGENT_CUDA_CHECK(cudaSetDevice(info.index));
    cudaDeviceProp prop{};
    EMERGENT_CUDA_CHECK(cudaGetDeviceProperties(&prop, info.index));
    info.name = prop.name;
    info.multiprocessors = prop.multiProcessorCount;
    info.memory_bytes = prop.totalGlobalMem;
    if (!selected) {
        EMERGENT_CUDA_CHECK(cudaFree(nullptr));  // creates the context, so its memory is counted
        memory_at_selection = device_memory_in_use();
        selected = true;
    }
    return info;
}

std::size_t device_memory_in_use() {
    std::size_t free = 0, total = 0;
    EMERGENT_CUDA_CHECK(cudaMemGetInfo(&free, &total));
    return total - free;
}

std::size_t run_device_bytes() {
    if (!selected) return 0;
    const std::size_t now = device_memory_in_use();
    return now > memory_at_selection ? now - memory_at_selection : 0;
}

}  // namespace emergent::gpu

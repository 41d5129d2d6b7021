// SPDX-License-Identifier: MIT
// Where a back end keeps its arrays (a GPU's memory, or host memory apart from the particle
// store for the checking back end), and the copies between it and the host.
#pragma once

#include <cstddef>
#include <memory>

namespace emergent::exec {

/// Where a back end keeps arrays, and the copies between it and the host.
class ArrayMemory {
public:
    virtual ~ArrayMemory() = default;
    virtual void* allocate(std::size_t bytes) = 0;
    virtual void release(void* p) noexcept = 0;
    virtual void to_backend(void* to, const void* from, std::size_t bytes) = 0;
    virtual void to_host(void* to, const void* from, std::size_t bytes) = 0;
    /// Host memory the back end copies to and from fastest, for staging MPI messages: page-
    /// locked on a CUDA device (its copies then run at full bus speed), plain elsewhere.
    virtual void* allocate_staging(std::size_t bytes) = 0;
    virtual void release_staging(void* p) noexcept = 0;
    /// A copy inside the back end's memory (not a transfer).
    virtual void within(void* to, const void* from, std::size_t bytes) = 0;
    /// What the memory is, for messages ("host (checking)", "CUDA device").
    virtual const char* name() const = 0;
};

/// Host memory apart from the store: the checking back end's "device".
std::unique_ptr<ArrayMemory> separate_host_memory();
/// The current CUDA device's memory; throws where the build or the machine has no CUDA.
std::unique_ptr<ArrayMemory> cuda_device_memory();

}  // namespace emergent::exec

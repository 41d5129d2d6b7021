// SPDX-License-Identifier: MIT
// The GPU entry points of a build without the CUDA back end: present nowhere, refused clearly.
#include <stdexcept>

#include "emergent/gpu.hpp"
#include "execution/array_memory.hpp"
#include "gpu/device_memory_use.hpp"

namespace emergent::gpu {

namespace {
[[noreturn]] void refuse() {
    throw std::runtime_error("execution on the GPU was requested but emergent was built without "
                             "the CUDA back end (configure with -DEMERGENT_CUDA=ON)");
}
}  // namespace

bool device_present() { return false; }
DeviceInfo select_device() { refuse(); }
std::size_t device_memory_in_use() { refuse(); }
std::size_t run_device_bytes() { return 0; }

}  // namespace emergent::gpu

namespace emergent::exec {
std::unique_ptr<ArrayMemory> cuda_device_memory() { gpu::refuse(); }
}  // namespace emergent::exec

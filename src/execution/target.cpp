// SPDX-License-Identifier: MIT
// The execution layer's non-template part: copies of single values to the host, and the
// refusal of a device loop that was compiled without CUDA.
#include <cstring>
#include <stdexcept>
#include <string>

#include "emergent/execution.hpp"

namespace emergent::exec {

void refuse_device_loop(const char* what) {
    throw std::runtime_error(std::string("a loop (") + what +
                             ") was asked to run on the CUDA device but its source was compiled "
                             "without CUDA; use backend=host, or build it with the CUDA back end");
}

void synchronize(const Target& target) {
    if (!target.device) return;
#if defined(__CUDACC__)
    EMERGENT_CUDA_CHECK(cudaStreamSynchronize(static_cast<cudaStream_t>(target.stream)));
#else
    refuse_device_loop("synchronize");
#endif
}

void read_from(const Target& target, void* to, const void* from, std::size_t bytes) {
    if (target.device) {
#if defined(__CUDACC__)
        EMERGENT_CUDA_CHECK(cudaMemcpyAsync(to, from, bytes, cudaMemcpyDeviceToHost,
                                            static_cast<cudaStream_t>(target.stream)));
        EMERGENT_CUDA_CHECK(cudaStreamSynchronize(static_cast<cudaStream_t>(target.stream)));
#else
        refuse_device_loop("read_from");
#endif
    } else {
        std::memcpy(to, from, bytes);
    }
    if (target.separate) count_scalar(bytes);
}

}  // namespace emergent::exec

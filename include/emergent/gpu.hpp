// SPDX-License-Identifier: MIT
// The CUDA device a rank uses, seen from host code (the engine's back end `cuda` runs on it).
// This header needs no CUDA headers; without the CUDA back end every entry point but
// device_present() throws a clear error.
#pragma once

#include <cstddef>
#include <string>

namespace emergent::gpu {

/// True when the CUDA back end is built and at least one CUDA device answers.
bool device_present();

struct DeviceInfo {
    int index = -1;
    std::string name;
    int multiprocessors = 0;
    std::size_t memory_bytes = 0;
};

/// Chooses the device for this process: local rank (Open MPI, SLURM, MPICH variables) modulo
/// the device count. Throws "no CUDA device" when CUDA was requested but none is present.
DeviceInfo select_device();

/// Device memory in use on the current device, by every process (total minus free).
std::size_t device_memory_in_use();

}  // namespace emergent::gpu

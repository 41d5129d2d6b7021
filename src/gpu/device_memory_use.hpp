// SPDX-License-Identifier: MIT
// The device memory a run holds, for the bytes-per-particle figure beside a GPU throughput.
#pragma once

#include <cstddef>

namespace emergent::gpu {

/// Device memory in use now less what was in use once the device was first selected (the CUDA
/// context's own and other processes'); 0 where no device was selected. One rank per device.
std::size_t run_device_bytes();

}  // namespace emergent::gpu

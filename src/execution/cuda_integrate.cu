// SPDX-License-Identifier: MIT
// Instantiates the integrator functors on the CUDA back end. The run-time GPU path (device
// residency, neighbour search, halo on the device) is built on these launchers.
#include "emergent/macros.hpp"
#include "execution/cuda_launch.cuh"
#include "integrate/velocity_verlet.hpp"

namespace emergent::exec {

template void for_each<integrate::KickDrift>(Cuda, std::size_t, const integrate::KickDrift&);
template void for_each<integrate::Kick>(Cuda, std::size_t, const integrate::Kick&);
template void for_each<integrate::ScaleVelocity>(Cuda, std::size_t,
                                                 const integrate::ScaleVelocity&);

}  // namespace emergent::exec

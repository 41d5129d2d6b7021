// SPDX-License-Identifier: MIT
// Instantiates the full-list pair-force functor on the CUDA back end (the same functor the CPU
// test runs through exec::Host and compares with the half-list loop).
#include "emergent/macros.hpp"
#include "execution/cuda_launch.cuh"
#include "force/lennard_jones.hpp"
#include "force/pair_full_list.hpp"

namespace emergent::exec {

template void for_each<force::PairForceFullList<force::LennardJones>>(
    Cuda, std::size_t, const force::PairForceFullList<force::LennardJones>&);

}  // namespace emergent::exec

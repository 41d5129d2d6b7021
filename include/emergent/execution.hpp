// SPDX-License-Identifier: MIT
// The thin execution layer: runs a per-particle functor as a CPU loop (here) or a CUDA grid
// (execution/cuda_launch.cuh). Physics lives in the functors, never in the launchers.
#pragma once

#include <cstddef>

namespace emergent::exec {

/// Host back end: a plain loop the compiler can vectorise.
struct Host {};

template <class Functor>
void for_each(Host, std::size_t n, const Functor& f) {
    for (std::size_t i = 0; i < n; ++i) f(i);
}

}  // namespace emergent::exec

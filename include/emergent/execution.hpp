// SPDX-License-Identifier: MIT
// The thin execution layer: runs a per-particle functor as a CPU loop (here) or a CUDA grid
// (execution/cuda_launch.cuh). Physics lives in the functors, never in the launchers.
#pragma once

#include <cstddef>

#include "emergent/macros.hpp"

namespace emergent::exec {

/// Two per-particle functors fused into one pass: second(i) runs right after first(i), so it
/// reads what first just wrote from cache rather than from memory. Only for functors that
/// touch particle i's data alone.
template <class First, class Second>
struct Then {
    First first;
    Second second;
    EMERGENT_HD void operator()(std::size_t i) const {
        first(i);
        second(i);
    }
};

/// Host back end: a plain loop the compiler can vectorise.
struct Host {};

template <class Functor>
void for_each(Host, std::size_t n, const Functor& f) {
    for (std::size_t i = 0; i < n; ++i) f(i);
}

}  // namespace emergent::exec

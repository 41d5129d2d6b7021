// SPDX-License-Identifier: MIT
// Counter-based random numbers: the value depends only on (seed, counters), never on which
// rank or thread asks, so initial states do not depend on the rank count.
#pragma once

#include <cmath>
#include <cstdint>

#include "emergent/macros.hpp"

namespace emergent {

/// SplitMix64 finaliser: a bijective mix with good avalanche.
EMERGENT_HD inline std::uint64_t mix64(std::uint64_t z) {
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

/// Uniform in (0, 1) from (seed, a, b).
EMERGENT_HD inline double uniform_open(std::uint64_t seed, std::uint64_t a, std::uint64_t b) {
    const std::uint64_t h = mix64(mix64(mix64(seed) ^ a) ^ b);
    return (static_cast<double>(h >> 11) + 0.5) * (1.0 / 9007199254740992.0);
}

/// Standard normal from (seed, a, b) by Box–Muller on two derived uniforms.
EMERGENT_HD inline double gaussian(std::uint64_t seed, std::uint64_t a, std::uint64_t b) {
    const double u1 = uniform_open(seed, a, 2 * b);
    const double u2 = uniform_open(seed, a, 2 * b + 1);
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
}

}  // namespace emergent

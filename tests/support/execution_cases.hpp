// SPDX-License-Identifier: MIT
// Inputs for the execution layer's tests, shared by the host tests and the device's comparison:
// the same cases on both back ends.
#pragma once

#include <cstdint>
#include <algorithm>
#include <random>
#include <vector>

namespace emergent::fixtures {

/// n doubles spread over many magnitudes (so the order of additions shows in the last bits).
inline std::vector<double> spread_values(std::size_t n, unsigned seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    std::uniform_int_distribution<int> e(-20, 20);
    std::vector<double> v(n);
    for (auto& x : v) x = std::ldexp(u(rng), e(rng));
    return v;
}

/// n keys below 2^bits, with many repeats (stability shows), and values 0..n-1.
inline void repeated_keys(std::size_t n, int bits, unsigned seed, std::vector<std::uint32_t>& keys,
                          std::vector<std::uint32_t>& values) {
    std::mt19937 rng(seed);
    const std::uint32_t range = bits >= 32 ? 0xffffffffu : (1u << bits) - 1;
    std::uniform_int_distribution<std::uint32_t> k(0, range);
    keys.resize(n);
    values.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        keys[i] = k(rng);
        values[i] = static_cast<std::uint32_t>(i);
    }
}

/// n 64-bit keys as a list build makes them, a cell above an id (cell < 2^cell_bits, ids
/// 0 .. n-1 in a shuffled order; values their positions), sorted by both at once.
inline void cell_and_id_keys(std::size_t n, int cell_bits, unsigned seed, std::vector<std::uint64_t>& keys,
                             std::vector<std::uint32_t>& values) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<std::uint32_t> cell(0, (1u << cell_bits) - 1);
    std::vector<std::uint32_t> ids(n);
    for (std::size_t i = 0; i < n; ++i) ids[i] = static_cast<std::uint32_t>(i);
    std::shuffle(ids.begin(), ids.end(), rng);
    keys.resize(n);
    values.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        keys[i] = static_cast<std::uint64_t>(cell(rng)) << 32 | ids[i];
        values[i] = static_cast<std::uint32_t>(i);
    }
}

}  // namespace emergent::fixtures

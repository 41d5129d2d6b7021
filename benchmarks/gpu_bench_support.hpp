// SPDX-License-Identifier: MIT
// What the GPU benchmark programs share: numeric options that fail with a line naming the
// option, and bringing a melting lattice to a temperature.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "emergent/gpu.hpp"

namespace emergent::bench {

/// The value of option `name` as a T (int, long or double); the whole text must be a number.
template <class T>
T number(const std::string& name, const std::string& text) {
    std::size_t used = 0;
    T value{};
    try {
        if constexpr (std::is_same_v<T, int>) value = std::stoi(text, &used);
        else if constexpr (std::is_same_v<T, long>) value = std::stol(text, &used);
        else value = std::stod(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || used != text.size())
        throw std::invalid_argument(name + "='" + text + "' is not a number");
    return value;
}

/// Runs `steps` steps in ten parts, rescaling to `temperature` after each: an fcc start loses
/// about half its kinetic energy to the lattice's potential energy as it melts.
inline void bring_to_temperature(gpu::PeriodicPairSystem& sys, double temperature, long steps) {
    for (int k = 0; k < 10; ++k) {
        sys.run(std::max(1L, steps / 10));
        const double t = 2 * sys.thermo().kinetic / (3 * double(sys.size()));
        sys.scale_velocities(std::sqrt(temperature / t));
    }
}

}  // namespace emergent::bench

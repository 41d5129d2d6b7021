// SPDX-License-Identifier: MIT
// Orthorhombic simulation region with per-axis periodicity.
#pragma once

#include "emergent/vec3.hpp"

namespace emergent {

/// Axis-aligned box [lo, hi) in each dimension; each axis is periodic or bounded.
struct Box {
    Vec3 lo{0, 0, 0};
    Vec3 hi{0, 0, 0};
    bool periodic[3] = {true, true, true};

    EMERGENT_HD Vec3 length() const { return hi - lo; }
    EMERGENT_HD Real volume() const {
        const Vec3 l = length();
        return l.x * l.y * l.z;
    }
};

}  // namespace emergent

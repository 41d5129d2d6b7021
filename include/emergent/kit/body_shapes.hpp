// SPDX-License-Identifier: MIT
// Sphere positions of rigid-body shapes that several scenes use.
#pragma once

#include <cmath>
#include <vector>

#include "emergent/vec3.hpp"

namespace emergent {

/// Four spheres at the corners of a regular tetrahedron, each `arm` from its centre (the
/// paper's granular particle: arm 0.6 small, 1.2 big).
inline std::vector<Vec3> regular_tetrahedron(double arm) {
    const double a = arm / std::sqrt(3.0);
    return {{a, a, a}, {a, -a, -a}, {-a, a, -a}, {-a, -a, a}};
}

}  // namespace emergent

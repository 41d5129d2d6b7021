// SPDX-License-Identifier: MIT
// Kinetic energy of a particle as a per-particle functor, for the execution layer's sums: the
// same code on CPU and GPU.
#pragma once

#include <cstdint>

#include "emergent/vec3.hpp"

namespace emergent::integrate {

/// m v^2 / 2 of a free particle; 0 for a sphere of a rigid body (its body counts it). body may
/// be null (no rigid bodies).
struct FreeKineticEnergy {
    const Vec3* v;
    const int* species;
    const double* mass;  ///< per species
    const std::int64_t* body;

    EMERGENT_HD double operator()(std::size_t i) const {
        if (body && body[i] >= 0) return 0;
        return 0.5 * mass[species[i]] * dot(v[i], v[i]);
    }
};

}  // namespace emergent::integrate

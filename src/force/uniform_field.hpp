// SPDX-License-Identifier: MIT
// A uniform field (gravity): force m g on every particle, potential energy -m g.x; as
// per-particle functors, the same code on CPU and GPU.
#pragma once

#include "emergent/vec3.hpp"

namespace emergent::force {

/// f += m g.
struct AddUniformField {
    Vec3* f;
    const int* species;
    const double* mass;  ///< per species
    Vec3 g;
    EMERGENT_HD void operator()(std::size_t i) const { f[i] += mass[species[i]] * g; }
};

/// -m g.x, the particle's potential energy in the field.
struct UniformFieldEnergy {
    const Vec3* x;
    const int* species;
    const double* mass;
    Vec3 g;
    EMERGENT_HD double operator()(std::size_t i) const { return -(mass[species[i]] * dot(g, x[i])); }
};

}  // namespace emergent::force

// SPDX-License-Identifier: MIT
// Velocity-Verlet stages as per-particle functors (the same code on CPU and GPU).
#pragma once

#include "emergent/vec3.hpp"

namespace emergent::integrate {

/// v += dt/2 f/m, then x += dt v: the first half of a velocity-Verlet step.
struct KickDrift {
    Vec3* x;
    Vec3* v;
    const Vec3* f;
    const int* species;
    const Real* inverse_mass;  ///< per species
    Real dt;

    EMERGENT_HD void operator()(std::size_t i) const {
        const Real h = 0.5 * dt * inverse_mass[species[i]];
        v[i].x += h * f[i].x;
        v[i].y += h * f[i].y;
        v[i].z += h * f[i].z;
        x[i].x += dt * v[i].x;
        x[i].y += dt * v[i].y;
        x[i].z += dt * v[i].z;
    }
};

/// v += dt/2 f/m with the new forces: the second half.
struct Kick {
    Vec3* v;
    const Vec3* f;
    const int* species;
    const Real* inverse_mass;
    Real dt;

    EMERGENT_HD void operator()(std::size_t i) const {
        const Real h = 0.5 * dt * inverse_mass[species[i]];
        v[i].x += h * f[i].x;
        v[i].y += h * f[i].y;
        v[i].z += h * f[i].z;
    }
};

/// v *= factor: global velocity rescaling (thermostats).
struct ScaleVelocity {
    Vec3* v;
    Real factor;
    EMERGENT_HD void operator()(std::size_t i) const { v[i] *= factor; }
};

}  // namespace emergent::integrate

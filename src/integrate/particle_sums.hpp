// SPDX-License-Identifier: MIT
// What the engine sums over particles (kinetic energy, momenta) and checks them for, as
// per-particle functors for the execution layer: the same code on CPU and GPU.
#pragma once

#include <cstdint>

#include "emergent/execution.hpp"
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

/// A kick-drift's measures, reduced in its pass: the free kinetic energy of the velocities it
/// started from (summed), the largest squared displacement since the list was built (a NaN
/// kept, as exec::transform_max does) and the largest squared drift those velocities alone
/// would make.
struct DriftMeasures {
    double kinetic = 0, moved_sq = 0, step_sq = 0;
    EMERGENT_HD DriftMeasures& operator+=(const DriftMeasures& o) {
        kinetic += o.kinetic;
        moved_sq = exec::max_keeping_nan(moved_sq, o.moved_sq);
        step_sq = exec::max_keeping_nan(step_sq, o.step_sq);
        return *this;
    }
};

/// Momentum and angular momentum (about the origin, unwrapped positions) of some particles.
struct Momenta {
    Vec3 linear{0, 0, 0}, angular{0, 0, 0};
    EMERGENT_HD Momenta& operator+=(const Momenta& o) {
        linear += o.linear;
        angular += o.angular;
        return *this;
    }
};

/// A free particle's Momenta (zero for a sphere of a rigid body; body may be null).
struct FreeMomenta {
    const Vec3* x;
    const Vec3* v;
    const Int3* image;
    const int* species;
    const double* mass;
    const std::int64_t* body;
    Vec3 box;  ///< lengths, to unwrap positions by their image counts

    EMERGENT_HD Momenta operator()(std::size_t i) const {
        if (body && body[i] >= 0) return Momenta{};
        const double m = mass[species[i]];
        const Int3 n = image[i];
        const Vec3 r = x[i] + Vec3{n.x * box.x, n.y * box.y, n.z * box.z};
        return Momenta{m * v[i], m * cross(r, v[i])};
    }
};

/// Mass, momentum and kinetic energy of some particles.
struct MassMotion {
    double mass = 0, kinetic = 0;
    Vec3 momentum{0, 0, 0};
    EMERGENT_HD MassMotion& operator+=(const MassMotion& o) {
        mass += o.mass;
        kinetic += o.kinetic;
        momentum += o.momentum;
        return *this;
    }
};

/// A free particle's MassMotion (zero for a constituent of a rigid body; body may be null).
struct FreeMassMotion {
    const Vec3* v;
    const int* species;
    const double* mass;
    const std::int64_t* body;

    EMERGENT_HD MassMotion operator()(std::size_t i) const {
        if (body && body[i] >= 0) return MassMotion{};
        const double m = mass[species[i]];
        return MassMotion{m, 0.5 * m * dot(v[i], v[i]), m * v[i]};
    }
};

/// True for a particle the guards must stop the run for: a non-finite position, velocity or
/// force, or a force above the bound (max_force_sq > 0).
struct UnfitState {
    const Vec3* x;
    const Vec3* v;
    const Vec3* f;
    double max_force_sq;

    EMERGENT_HD bool operator()(std::size_t i) const {
        // One sum is non-finite if any term is: a single test per particle on the fast path.
        // sum - sum is 0 exactly when sum is finite, NaN otherwise (isfinite without <cmath>,
        // the same on host and device).
        const double sum = x[i].x + x[i].y + x[i].z + v[i].x + v[i].y + v[i].z + f[i].x + f[i].y + f[i].z;
        if (!(sum - sum == 0)) return true;
        return max_force_sq > 0 && dot(f[i], f[i]) > max_force_sq;
    }
};

}  // namespace emergent::integrate

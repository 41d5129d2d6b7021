// SPDX-License-Identifier: MIT
// The stages every splitting integrator is made of (velocity Verlet, Omelyan's minimum-error
// scheme), as per-particle functors: the same code on CPU and GPU. A stage's kick and drift
// durations are given, so one functor serves every scheme.
#pragma once

#include "emergent/vec3.hpp"

namespace emergent::integrate {

/// v += kick f/m, then x += drift v.
struct KickDrift {
    Vec3* x;
    Vec3* v;
    const Vec3* f;
    const int* species;
    const Real* inverse_mass;  ///< per species
    Real kick, drift;          ///< durations (velocity Verlet: dt/2 and dt)

    EMERGENT_HD void operator()(std::size_t i) const {
        const Real h = kick * inverse_mass[species[i]];
        v[i].x += h * f[i].x;
        v[i].y += h * f[i].y;
        v[i].z += h * f[i].z;
        x[i].x += drift * v[i].x;
        x[i].y += drift * v[i].y;
        x[i].z += drift * v[i].z;
    }
};

/// v += kick f/m with the new forces (velocity Verlet: the second half kick, dt/2).
struct Kick {
    Vec3* v;
    const Vec3* f;
    const int* species;
    const Real* inverse_mass;
    Real kick;

    EMERGENT_HD void operator()(std::size_t i) const {
        const Real h = kick * inverse_mass[species[i]];
        v[i].x += h * f[i].x;
        v[i].y += h * f[i].y;
        v[i].z += h * f[i].z;
    }
};

/// A velocity rescaling v0 -> factor v0 of the velocities a KickDrift started from, applied
/// after it: with v0 = v - kick f/m, v += change v0 and x += drift change v0 (change = factor
/// - 1), the state the KickDrift would have left from the rescaled velocities (up to rounding).
/// So a thermostat acting at the start of a step can take its sum in the vote after the drift.
struct RescaleBeforeKickDrift {
    Vec3* x;
    Vec3* v;
    const Vec3* f;
    const int* species;
    const Real* inverse_mass;
    Real kick, drift, change;

    EMERGENT_HD void operator()(std::size_t i) const {
        const Real h = kick * inverse_mass[species[i]];
        const Vec3 v0{v[i].x - h * f[i].x, v[i].y - h * f[i].y, v[i].z - h * f[i].z};
        v[i].x += change * v0.x;
        v[i].y += change * v0.y;
        v[i].z += change * v0.z;
        x[i].x += drift * change * v0.x;
        x[i].y += drift * change * v0.y;
        x[i].z += drift * change * v0.z;
    }
};

/// a[i] = 0: forces cleared before the terms add theirs.
struct ZeroVector {
    Vec3* a;
    EMERGENT_HD void operator()(std::size_t i) const { a[i] = Vec3{0, 0, 0}; }
};

/// v *= factor: global velocity rescaling (thermostats).
struct ScaleVelocity {
    Vec3* v;
    Real factor;
    EMERGENT_HD void operator()(std::size_t i) const { v[i] *= factor; }
};

/// v = u + factor (v - u) for free particles (constituents of bodies are left alone): a
/// thermostat acting on a bath of free particles about their mean velocity u, so that their
/// momentum, and the total, stay as they are.
struct ScaleFreeAboutMean {
    Vec3* v;
    const std::int64_t* body;
    Vec3 mean;
    Real factor;
    EMERGENT_HD void operator()(std::size_t i) const {
        if (body[i] >= 0) return;
        v[i] = mean + factor * (v[i] - mean);
    }
};

}  // namespace emergent::integrate

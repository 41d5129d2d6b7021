// SPDX-License-Identifier: MIT
// The wall-layer thermostat's passes over particles, as functors for the execution layer: the
// layer's sums, then the rescaling of its velocities about their mean flow along the wall.
#pragma once

#include "emergent/vec3.hpp"

namespace emergent::thermostat {

/// Mass, momentum, twice the kinetic energy and count of some particles.
struct LayerSums {
    double mass = 0;
    Vec3 momentum{0, 0, 0};
    double twice_kinetic = 0, count = 0;
    EMERGENT_HD LayerSums& operator+=(const LayerSums& o) {
        mass += o.mass;
        momentum += o.momentum;
        twice_kinetic += o.twice_kinetic;
        count += o.count;
        return *this;
    }
};

/// Whether a position lies in the layer lo <= x[axis] < hi.
struct InLayer {
    int axis;
    double lo, hi;
    EMERGENT_HD bool operator()(const Vec3& x) const {
        const double s = x[axis];
        return s >= lo && s < hi;
    }
};

/// Particle i's LayerSums if it is in the layer, else nothing.
struct LayerMember {
    const Vec3* x;
    const Vec3* v;
    const int* species;
    const double* mass;
    InLayer layer;
    EMERGENT_HD LayerSums operator()(std::size_t i) const {
        if (!layer(x[i])) return LayerSums{};
        const double m = mass[species[i]];
        return LayerSums{m, m * v[i], m * dot(v[i], v[i]), 1};
    }
};

/// v = factor (v - drift) for the layer's particles.
struct RescaleLayer {
    const Vec3* x;
    Vec3* v;
    InLayer layer;
    double factor;
    Vec3 drift;
    EMERGENT_HD void operator()(std::size_t i) const {
        if (layer(x[i])) v[i] = factor * (v[i] - drift);
    }
};

}  // namespace emergent::thermostat

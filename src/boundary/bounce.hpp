// SPDX-License-Identifier: MIT
// A particle that ended a drift beyond a wall, returned by the wall's rule: moved back along
// its path to the impact point, given the wall's new velocity there, and sent on for the rest
// of the step. As functors for the execution layer (the same code on CPU and GPU); the wall's
// tally of what it exchanged is their sum.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

#include "boundary/wall_geometry.hpp"
#include "emergent/box.hpp"
#include "emergent/random.hpp"

namespace emergent::boundary {

/// What bounces exchanged with a wall, and the first particle (by index) a wall could not
/// return inside.
struct BounceTally {
    long long hits = 0;
    Vec3 momentum{0, 0, 0};
    double angular_momentum = 0, energy = 0;
    std::size_t first_fault = std::numeric_limits<std::size_t>::max();

    EMERGENT_HD BounceTally& operator+=(const BounceTally& o) {
        hits += o.hits;
        momentum += o.momentum;
        angular_momentum += o.angular_momentum;
        energy += o.energy;
        if (o.first_fault < first_fault) first_fault = o.first_fault;
        return *this;
    }
};

/// Specular reflection of the velocity w relative to the wall.
struct Reflect {
    EMERGENT_HD Vec3 operator()(const Vec3& w, const Vec3& n, const Vec3&, std::int64_t, double) const {
        return w - (2 * dot(w, n)) * n;
    }
};

/// x on a grid of 2^-30 (about 1e-9 sigma): the coin still flips with any visible change of
/// the impact point, but not with the round-off by which runs on different rank counts differ.
/// (An absolute grid, not relative bits: an impact on a wall at 0 has a coordinate of order
/// the round-off itself, whose bits are noise.)
EMERGENT_HD inline std::uint64_t impact_bits(double x) {
    return static_cast<std::uint64_t>(std::llround(std::ldexp(x, 30)));
}

/// A thermal wall: the direction reflected or reversed by a deterministic but sensitive
/// function of the impact point, the speed drawn from the wall's temperature.
struct Rethermalise {
    double kT;
    std::uint64_t seed, step;

    EMERGENT_HD Vec3 operator()(const Vec3& w, const Vec3& n, const Vec3& hit, std::int64_t id,
                                double m) const {
        // Reflection or reversal, from the bits of the impact point.
        const std::uint64_t h =
            mix64(impact_bits(hit.x) ^ mix64(impact_bits(hit.y) ^ mix64(impact_bits(hit.z))));
        const double wn = dot(w, n);
        Vec3 out = (h >> 32) & 1 ? -1.0 * w : w - (2 * wn) * n;
        if (!(wn < 0)) out = n;  // grazing or outgoing: leave along the normal
        // s^2 m / kT is chi-squared with 4 degrees of freedom: -2 ln(u1 u2).
        const double u1 = uniform_open(seed, static_cast<std::uint64_t>(id), 2 * step);
        const double u2 = uniform_open(seed, static_cast<std::uint64_t>(id), 2 * step + 1);
        const double speed = std::sqrt(-2.0 * (kT / m) * std::log(u1 * u2));
        return (speed / std::sqrt(dot(out, out))) * out;
    }
};

/// Particle i beyond the wall (the caller selects those with Beyond), returned by NewVelocity.
template <class NewVelocity>
struct Bounce {
    WallGeometry wall;
    NewVelocity new_velocity;
    Vec3* x;
    Vec3* v;
    const int* species;
    const double* mass;
    const std::int64_t* id;
    double dt, time;
    bool has_box;  ///< impact points are taken at their primary image (rank-count independent)
    Box box;

    EMERGENT_HD BounceTally operator()(std::size_t i) const {
        Vec3 xi = x[i];
        const Vec3 vi = v[i];
        const double m = mass[species[i]];
        const Vec3 start = xi - dt * vi;  // the drift moved it by v dt in a straight line
        double t = wall.impact_time(start, vi, dt);
        Vec3 hit = start + t * vi;
        if (!wall.on_fluid_side(start)) {
            // Its path this step was already bent by another wall (a corner): put it on this
            // wall at the nearest point, at the end of the step.
            t = dt;
            hit = xi - wall.gap(xi) * wall.normal(xi);
        }
        const Vec3 n = wall.normal(hit);
        const Vec3 u = wall.velocity_at(hit, time);
        const Vec3 v_new = u + new_velocity(vi - u, n, has_box ? box.primary_image(hit) : hit, id[i], m);
        xi = hit + (dt - t) * v_new;
        // A grazing departure from a curved wall may end a hair beyond it: keep it on the wall.
        if (!wall.on_fluid_side(xi)) xi = hit + (1e-12 * (1 + std::fabs(wall.gap(xi)))) * n;
        const Vec3 dp = m * (v_new - vi);
        BounceTally tally;
        tally.hits = 1;
        tally.momentum = dp;
        tally.angular_momentum = wall.angular_component(hit, dp);
        tally.energy = 0.5 * m * (dot(v_new, v_new) - dot(vi, vi));
        const double sum = xi.x + xi.y + xi.z;
        if (!wall.on_fluid_side(xi) || !(sum - sum == 0)) tally.first_fault = i;
        x[i] = xi;
        v[i] = v_new;
        return tally;
    }
};

/// Selects the particles beyond the wall.
template <class Beyond>
struct IsBeyond {
    Beyond beyond;
    const Vec3* x;
    EMERGENT_HD bool operator()(std::size_t i) const { return beyond(x[i]); }
};

}  // namespace emergent::boundary

// SPDX-License-Identifier: MIT
// A rotating cylinder wall made rough by spheres embedded in it (paper: the drum's curved
// wall): the wall spheres' positions at any time, and the contact force a sphere inside the
// drum feels from them and from the smooth surface behind them. Written once for CPU and GPU.
#pragma once

#include <algorithm>
#include <cmath>

#include "emergent/force_term.hpp"
#include "emergent/macros.hpp"
#include "emergent/vec3.hpp"
#include "force/granular_contact.hpp"

namespace emergent::force {

/// The wall spheres: centres on the cylinder r = radius about the z axis, on a staggered
/// (triangular) grid: `n_around` spheres per ring, rings `row_spacing` apart along z, every
/// other ring turned by half a step, the whole grid turned by omega t. The grid is a function of
/// time, not stored particles: it moves rigidly with the wall by construction, needs no
/// migration, and a particle finds its few candidate wall spheres by index arithmetic.
struct RoughCylinderLattice {
    Real radius = 1, z_first = 0, row_spacing = 1, angle_step = 1, omega = 0;
    int n_around = 1, n_rows = 0;

    /// Angle of sphere j of ring k at time t.
    EMERGENT_HD Real angle(int k, int j, Real t) const {
        return (j + 0.5 * (k & 1)) * angle_step + omega * t;
    }
    EMERGENT_HD Vec3 sphere(int k, int j, Real t) const {
        const Real a = angle(k, j, t);
        return {radius * std::cos(a), radius * std::sin(a), z_first + k * row_spacing};
    }
    /// Velocity of the wall material at x: omega z^ x x.
    EMERGENT_HD Vec3 wall_velocity(const Vec3& x) const { return {-omega * x.y, omega * x.x, 0}; }
};

/// The grid of a RoughCylinder (see make_rough_cylinder_wall).
inline RoughCylinderLattice rough_cylinder_lattice(const RoughCylinder& w) {
    constexpr double kTwoPi = 6.283185307179586;
    RoughCylinderLattice l;
    l.radius = w.radius;
    l.omega = w.omega;
    l.n_around = static_cast<int>(std::lround(kTwoPi * w.radius / w.spacing));
    l.angle_step = kTwoPi / l.n_around;
    // Rings of a triangular grid are sqrt(3)/2 of the spacing apart, stretched slightly so a
    // whole number of them spans the length. The end rings keep one row spacing from the ends:
    // a ring closer to an end cap leaves less than a sphere's room in the corner, and the
    // turning wall spheres would wedge the spheres sitting there against the cap.
    const double ideal = 0.5 * std::sqrt(3.0) * w.spacing;
    const double span = std::max(0.0, w.z_hi - w.z_lo - 2 * ideal);
    const int gaps = static_cast<int>(std::lround(span / ideal));
    l.n_rows = gaps + 1;
    l.row_spacing = gaps > 0 ? span / gaps : ideal;
    l.z_first = gaps > 0 ? w.z_lo + ideal : 0.5 * (w.z_lo + w.z_hi);
    return l;
}

/// Contact force on one sphere (centre x, velocity v, diameter d) from the rough wall at time t:
/// every wall sphere within r_c = range (d + d_wall) / 2, plus the smooth cylinder surface
/// through the wall spheres' centres (r_c = range d / 2), which keeps spheres from slipping
/// through the gaps of the grid. Adds energy and overlap to *tally when it is not null.
template <bool Damping, bool Friction>
EMERGENT_HD inline Vec3 rough_wall_force(const RoughCylinderLattice& w, const GranularPair& p,
                                         Real range, Real d_wall, const Vec3& x, const Vec3& v,
                                         Real d, Real t, ContactTally* tally) {
    Vec3 f{0, 0, 0};
    const Real r = std::sqrt(x.x * x.x + x.y * x.y);
    const Real reach = 0.5 * range * (d + d_wall);
    if (!(r > w.radius - reach)) return f;  // also false for NaN: the guard reports those
    // The smooth surface, normal pointing inwards.
    const Real rc_surface = 0.5 * range * d, gap = w.radius - r;
    if (gap < rc_surface) {
        const Vec3 n{-x.x / r, -x.y / r, 0};
        const Vec3 at = (w.radius / r) * Vec3{x.x, x.y, 0};
        const Real overlap = rc_surface - gap;
        f += contact_force<Damping, Friction>(n, overlap, v - w.wall_velocity(at), p);
        if (tally) tally->add(p.k_n, overlap, d);
    }
    // Rings within reach along z, and within them the spheres within reach around.
    const Real zk = (x.z - w.z_first) / w.row_spacing, dk = reach / w.row_spacing;
    int k0 = static_cast<int>(std::floor(zk - dk)), k1 = static_cast<int>(std::ceil(zk + dk));
    k0 = k0 < 0 ? 0 : k0;
    k1 = k1 > w.n_rows - 1 ? w.n_rows - 1 : k1;
    const Real phi = std::atan2(x.y, x.x);
    int dj = 1 + static_cast<int>(reach / (w.radius * w.angle_step));
    if (2 * dj + 2 > w.n_around) dj = (w.n_around - 2) / 2;  // never the same sphere twice
    for (int k = k0; k <= k1; ++k) {
        const Real u = (phi - w.angle(k, 0, t)) / w.angle_step;
        const int j0 = static_cast<int>(std::floor(u));
        for (int j = j0 - dj; j <= j0 + dj + 1; ++j) {
            const Vec3 xw = w.sphere(k, j, t);  // j outside 0..n_around-1 is the same sphere turned
            const Vec3 s = x - xw;
            const Real s2 = dot(s, s);
            if (s2 >= reach * reach) continue;
            const Real dist = std::sqrt(s2);
            f += contact_force<Damping, Friction>((1 / dist) * s, reach - dist,
                                                  v - w.wall_velocity(xw), p);
            if (tally) tally->add(p.k_n, reach - dist, 0.5 * (d + d_wall));
        }
    }
    return f;
}

}  // namespace emergent::force

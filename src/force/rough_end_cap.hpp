// SPDX-License-Identifier: MIT
// A rotating flat end cap made rough by spheres embedded in it (option of the drum: rough
// rotating end caps): the spheres' positions at any time and the force they exert. Written
// once for CPU and GPU.
#pragma once

#include <cmath>

#include "emergent/force_term.hpp"
#include "emergent/macros.hpp"
#include "emergent/vec3.hpp"
#include "force/granular_contact.hpp"

namespace emergent::force {

/// The cap's spheres: centres in the plane z = z_cap on a triangular grid (spacing a, rows
/// a sqrt(3)/2 apart, alternate rows shifted by a/2) fixed in the cap and turned by omega t
/// about the z axis; only sites within `radius` of the axis carry a sphere. Like the curved
/// wall's grid, a function of time found by index arithmetic, not stored particles.
struct RoughCapLattice {
    Real z_cap = 0, radius = 1, spacing = 1, row_spacing = 1, omega = 0;

    EMERGENT_HD bool has(int i, int j) const {
        const Real u = (i + 0.5 * (j & 1)) * spacing, w = j * row_spacing;
        return u * u + w * w <= radius * radius;
    }
    /// Site (i, j) at time t.
    EMERGENT_HD Vec3 sphere(int i, int j, Real t) const {
        const Real u = (i + 0.5 * (j & 1)) * spacing, w = j * row_spacing;
        const Real c = std::cos(omega * t), s = std::sin(omega * t);
        return {c * u - s * w, s * u + c * w, z_cap};
    }
    EMERGENT_HD Vec3 wall_velocity(const Vec3& x) const { return {-omega * x.y, omega * x.x, 0}; }
};

/// The grid of a RoughEndCap (see make_rough_end_cap).
inline RoughCapLattice rough_cap_lattice(const RoughEndCap& c) {
    RoughCapLattice l;
    l.z_cap = c.z;
    l.radius = c.radius;
    l.spacing = c.spacing;
    l.row_spacing = 0.5 * std::sqrt(3.0) * c.spacing;
    l.omega = c.omega;
    return l;
}

/// Contact force on one sphere (centre x, velocity v, diameter d) from the cap's spheres at
/// time t, r_c = range (d + d_cap) / 2. Adds energy and overlap to *tally when not null.
template <bool Damping, bool Friction>
EMERGENT_HD inline Vec3 rough_wall_force(const RoughCapLattice& cap, const GranularPair& p,
                                         Real range, Real d_cap, const Vec3& x, const Vec3& v,
                                         Real d, Real t, ContactTally* tally) {
    Vec3 f{0, 0, 0};
    const Real reach = 0.5 * range * (d + d_cap);
    if (!(std::fabs(x.z - cap.z_cap) < reach)) return f;
    // The sphere's place in the cap's own (turned) frame.
    const Real c = std::cos(cap.omega * t), s = std::sin(cap.omega * t);
    const Real u = c * x.x + s * x.y, w = -s * x.x + c * x.y;
    const int j0 = static_cast<int>(std::floor((w - reach) / cap.row_spacing));
    const int j1 = static_cast<int>(std::ceil((w + reach) / cap.row_spacing));
    for (int j = j0; j <= j1; ++j) {
        const Real shift = 0.5 * (j & 1);
        const int i0 = static_cast<int>(std::floor((u - reach) / cap.spacing - shift));
        const int i1 = static_cast<int>(std::ceil((u + reach) / cap.spacing - shift));
        for (int i = i0; i <= i1; ++i) {
            if (!cap.has(i, j)) continue;
            const Vec3 xw = cap.sphere(i, j, t);
            const Vec3 sep = x - xw;
            const Real s2 = dot(sep, sep);
            if (s2 >= reach * reach) continue;
            const Real dist = std::sqrt(s2);
            f += contact_force<Damping, Friction>((1 / dist) * sep, reach - dist,
                                                  v - cap.wall_velocity(xw), p);
            if (tally) tally->add(p.k_n, reach - dist, 0.5 * (d + d_cap));
        }
    }
    return f;
}

}  // namespace emergent::force

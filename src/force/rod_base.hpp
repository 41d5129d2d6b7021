// SPDX-License-Identifier: MIT
// A vibrating base built from thin rods laid along a periodic profile (paper: the sawtooth base
// of the vibrated layer): where the rods are, and the force a sphere feels from those within
// reach. Written once for CPU and GPU; the rods are index arithmetic, not stored particles.
#pragma once

#include <cmath>

#include "emergent/force_term.hpp"
#include "emergent/macros.hpp"
#include "emergent/vec3.hpp"
#include "force/granular_contact.hpp"

namespace emergent::force {

/// The rods of one period of the profile, edge by edge, in the profile plane (u, z): edge e
/// holds rods at start[e] + j step[e], j = 0 .. count[e] - 1 (its end vertex is the next
/// edge's first rod). Period p repeats them shifted by p * period along u. By value: small
/// enough to travel with a kernel's arguments.
constexpr int kRodBaseMaxEdges = 4;
struct RodLattice {
    Real start_u[kRodBaseMaxEdges], start_z[kRodBaseMaxEdges];
    Real step_u[kRodBaseMaxEdges], step_z[kRodBaseMaxEdges];
    int count[kRodBaseMaxEdges];
    int n_edges = 0;
    Real period = 1;
    Real u_lo = 0, u_hi = 0;  ///< rods exist where u_lo <= u <= u_hi (the container's floor)
    Real top = 0;             ///< highest rod centre above the base level
    bool rings = false;       ///< rods are rings about the z axis (u = r), else lines along y (u = x)
    bool backing = false;     ///< a smooth surface along the profile behind the rods
    Real amplitude = 0, angular_frequency = 0;  ///< base level z_b(t) = a sin(w t)

    EMERGENT_HD Real level(Real t) const { return amplitude * std::sin(angular_frequency * t); }
    EMERGENT_HD Real level_speed(Real t) const {
        return amplitude * angular_frequency * std::cos(angular_frequency * t);
    }
};

/// The lattice of a RodBase; InputError naming what does not fit.
RodLattice rod_lattice(const RodBase& base);

/// The backing: a smooth surface along the profile (through the rods' centres) that a sphere
/// meets at r_c = range d / 2, less than the rods' reach, so it acts only on a sphere pressed
/// between the rods deeper than they let it go, and pushes back out one that got below the
/// profile. Without it a thick or strongly shaken layer can squeeze a grain through the rods.
/// Periods first..last of the profile are searched; the profile runs toward +u, so each edge's
/// left normal points out of the base.
template <bool Damping>
EMERGENT_HD inline Vec3 backing_force(const RodLattice& b, const GranularPair& p, Real range, Real r,
                                      Real z, Real cx, Real cy, const Vec3& v_rel, Real d, int first,
                                      int last, ContactTally* tally) {
    const Real rc = 0.5 * range * d;
    Real best = 1e300, hu = 0, hz = 0, nu = 0, nz = 1;
    for (int m = first; m <= last; ++m)
        for (int e = 0; e < b.n_edges; ++e) {
            if (b.count[e] == 0) continue;
            const Real au = b.start_u[e] + m * b.period, az = b.start_z[e];
            const Real eu = b.step_u[e] * b.count[e], ez = b.step_z[e] * b.count[e];
            const Real len2 = eu * eu + ez * ez;
            Real s = ((r - au) * eu + (z - az) * ez) / len2;
            s = s < 0 ? 0 : (s > 1 ? 1 : s);
            const Real gu = r - (au + s * eu), gz = z - (az + s * ez);
            const Real dist2 = gu * gu + gz * gz;
            if (dist2 < best) {
                best = dist2, hu = gu, hz = gz;
                const Real len = std::sqrt(len2);
                nu = -ez / len, nz = eu / len;  // left normal: out of the base
            }
        }
    if (!(best < 1e299)) return {0, 0, 0};
    const Real dist = std::sqrt(best);
    // Outside the base where the sphere is above the profile's height there (at a vertex the
    // nearest edge's normal alone cannot tell).
    const Real w = r - std::floor(r / b.period) * b.period;
    bool outside = true;
    for (int e = 0; e < b.n_edges; ++e) {
        const Real eu = b.step_u[e] * b.count[e];
        if (b.count[e] == 0 || !(eu > 0) || w < b.start_u[e] || w > b.start_u[e] + eu) continue;
        outside = z > b.start_z[e] + (w - b.start_u[e]) / eu * (b.step_z[e] * b.count[e]);
        break;
    }
    if (outside && dist >= rc) return {0, 0, 0};
    // Outside: along the shortest way to the surface; below it: back out along the nearest
    // edge's outward normal.
    Real ou = nu, oz = nz, overlap = rc + dist;
    if (outside) {
        if (dist > 0) ou = hu / dist, oz = hz / dist;
        overlap = rc - dist;
    }
    const Vec3 n{ou * cx, ou * cy, oz};
    if (tally) tally->add(p.k_n, overlap, d);
    return contact_force<Damping, false>(n, overlap, v_rel, p);
}

/// Force on a sphere (centre x, velocity v, diameter d) at time t from every rod within
/// r_c = range (d + d_rod) / 2, acting in the plane normal to the rod (overlap repulsion and
/// normal damping of the contact law, no sliding friction). Adds energy and overlap to *tally
/// when it is not null.
template <bool Damping>
EMERGENT_HD inline Vec3 rod_base_force(const RodLattice& b, const GranularPair& p, Real range,
                                       Real d_rod, const Vec3& x, const Vec3& v, Real d, Real t,
                                       ContactTally* tally) {
    Vec3 f{0, 0, 0};
    const Real reach = 0.5 * range * (d + d_rod);
    const Real z = x.z - b.level(t);
    if (!(z < b.top + reach)) return f;  // also false for NaN: the guard reports those
    const Real r = b.rings ? std::sqrt(x.x * x.x + x.y * x.y) : x.x;
    // Rings: the radial direction (any one on the axis itself, where no ring reaches).
    const Real cx = b.rings && r > 0 ? x.x / r : 1, cy = b.rings && r > 0 ? x.y / r : 0;
    const Vec3 base_velocity{0, 0, b.level_speed(t)};
    const int first = static_cast<int>(std::floor((r - reach) / b.period)) - 1;
    const int last = static_cast<int>(std::floor((r + reach) / b.period));
    for (int m = first; m <= last; ++m)
        for (int e = 0; e < b.n_edges; ++e) {
            // Rods of this edge within reach: an interval of j around the foot of the
            // perpendicular from the sphere onto the edge's line.
            const Real au = b.start_u[e] + m * b.period, az = b.start_z[e];
            const Real su = b.step_u[e], sz = b.step_z[e];
            const Real step2 = su * su + sz * sz;
            const Real du = r - au, dz = z - az;
            const Real s = (du * su + dz * sz) / step2;
            const Real pu = du - s * su, pz = dz - s * sz;
            const Real off2 = pu * pu + pz * pz;
            if (off2 >= reach * reach) continue;
            const Real half = std::sqrt((reach * reach - off2) / step2);
            int j0 = static_cast<int>(std::ceil(s - half)), j1 = static_cast<int>(std::floor(s + half));
            j0 = j0 < 0 ? 0 : j0;
            j1 = j1 > b.count[e] - 1 ? b.count[e] - 1 : j1;
            for (int j = j0; j <= j1; ++j) {
                const Real ru = au + j * su;
                if (ru < b.u_lo || ru > b.u_hi) continue;
                const Real gu = r - ru, gz = z - (az + j * sz);
                const Real dist2 = gu * gu + gz * gz;
                if (dist2 >= reach * reach) continue;
                const Real dist = std::sqrt(dist2);
                const Vec3 n{gu / dist * cx, gu / dist * cy, gz / dist};
                f += contact_force<Damping, false>(n, reach - dist, v - base_velocity, p);
                if (tally) tally->add(p.k_n, reach - dist, 0.5 * (d + d_rod));
            }
        }
    if (b.backing) f += backing_force<Damping>(b, p, range, r, z, cx, cy, v - base_velocity, d, first, last, tally);
    return f;
}

/// The rod base's contact law on one particle (force::TalliedWallForce applies it to each).
template <bool Damping>
struct RodBaseLaw {
    RodLattice base;
    GranularPair p;
    Real range, d_rod, time;
    EMERGENT_HD Vec3 operator()(const Vec3& x, const Vec3& v, Real d, ContactTally* tally) const {
        return rod_base_force<Damping>(base, p, range, d_rod, x, v, d, time, tally);
    }
};

/// A smooth cylindrical wall about the z axis of radius `radius` holding spheres inside: the
/// contact law at r_c = range d / 2 from the surface (no friction: the paper's smooth walls).
template <bool Sample, bool Damping>
struct CylinderWallForce {
    const Vec3* x;
    const Vec3* v;
    const Real* diameter;
    Vec3* f;
    Real radius, range;
    GranularPair p;
    Real* energy = nullptr;
    Real* overlap = nullptr;

    EMERGENT_HD void operator()(std::size_t i) const {
        const Real r = std::sqrt(x[i].x * x[i].x + x[i].y * x[i].y);
        const Real rc = 0.5 * range * diameter[i], gap = radius - r;
        if (!(gap < rc) || !(r > 0)) {
            if constexpr (Sample) energy[i] = overlap[i] = 0;
            return;
        }
        const Vec3 n{-x[i].x / r, -x[i].y / r, 0};
        f[i] += contact_force<Damping, false>(n, rc - gap, v[i], p);
        if constexpr (Sample) {
            energy[i] = 0.5 * p.k_n * (rc - gap) * (rc - gap);
            overlap[i] = (rc - gap) / diameter[i];
        }
    }
};

}  // namespace emergent::force

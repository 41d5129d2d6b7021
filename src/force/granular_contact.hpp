// SPDX-License-Identifier: MIT
// The granular contact law (paper eqs. 2, 7, 8), written once for CPU and GPU.
#pragma once

#include <cmath>
#include <string>

#include "emergent/force_term.hpp"
#include "emergent/vec3.hpp"

namespace emergent::force {

/// Force on particle i from a contact with unit normal n (pointing from the partner to i),
/// overlap `overlap` > 0 and relative velocity v_rel = v_i - v_partner. Damping and friction
/// are compile-time features: a model without them carries no arithmetic for them.
template <bool Damping, bool Friction>
EMERGENT_HD inline Vec3 contact_force(const Vec3& n, Real overlap, const Vec3& v_rel,
                                      const GranularPair& p) {
    Vec3 f = (p.k_n * overlap) * n;  // elastic: -du/dr of (k_n/2)(r_c - r)^2
    if constexpr (Damping) f -= (p.gamma_n * dot(n, v_rel)) * n;
    if constexpr (Friction) {
        const Vec3 v_t = v_rel - dot(n, v_rel) * n;
        const Real speed = std::sqrt(dot(v_t, v_t));
        if (speed > 0) {
            // Viscous sliding, capped by Coulomb's mu |f_l + f_d|.
            const Real viscous = p.gamma_s * speed, coulomb = p.mu * std::sqrt(dot(f, f));
            f -= ((viscous < coulomb ? viscous : coulomb) / speed) * v_t;
        }
    }
    return f;
}

/// The contact laws of up to kContactTableSpecies species by value (n_species^2 entries,
/// row-major): small enough to travel with a kernel's arguments, so no table lives in host
/// memory while a device loop reads it.
constexpr int kContactTableSpecies = 4;
struct ContactTable {
    GranularPair pair[kContactTableSpecies * kContactTableSpecies];
    EMERGENT_HD const GranularPair& operator[](int k) const { return pair[k]; }
};

/// Force on a sphere from a flat wall normal to `axis` (the sphere on the side `side`, +1 or
/// -1), moving with `wall_velocity`, for a sphere of contact range r_c = range d_i / 2. With
/// Sample, energy[i] and overlap[i] (in diameters) get the contact's elastic energy and overlap,
/// 0 without contact.
template <bool Sample, bool Damping, bool Friction>
struct PlaneWallForce {
    const Vec3* x;
    const Vec3* v;
    const Real* diameter;
    Vec3* f;
    int axis;
    Real side, position, range;
    GranularPair p;
    Vec3 wall_velocity;
    Real* energy = nullptr;
    Real* overlap = nullptr;

    EMERGENT_HD void operator()(std::size_t i) const {
        const Real h = side * (x[i][axis] - position);
        const Real rc = 0.5 * range * diameter[i];
        if (h >= rc) {
            if constexpr (Sample) energy[i] = overlap[i] = 0;
            return;
        }
        Vec3 n{0, 0, 0};
        n[axis] = side;
        f[i] += contact_force<Damping, Friction>(n, rc - h, v[i] - wall_velocity, p);
        if constexpr (Sample) {
            energy[i] = 0.5 * p.k_n * (rc - h) * (rc - h);
            overlap[i] = (rc - h) / diameter[i];
        }
    }
};

/// Throws InputError naming `what` unless k_n > 0 and gamma_n, gamma_s, mu >= 0.
void check_granular_pair(const GranularPair& p, const std::string& what);

/// What sampling steps add up over contacts: elastic energy and the largest overlap in units
/// of the contact's sphere diameter (the pair's mean diameter).
struct ContactTally {
    Real energy = 0, max_overlap = 0;
    EMERGENT_HD void add(Real k_n, Real overlap, Real diameter) {
        energy += 0.5 * k_n * overlap * overlap;
        if (overlap > max_overlap * diameter) max_overlap = overlap / diameter;
    }
};

/// Compile-time features of the contact loop.
template <bool Sample, bool Damping, bool Friction, bool SpeciesTable>
struct ContactFeatures {
    static constexpr bool sample = Sample, damping = Damping, friction = Friction,
                          species_table = SpeciesTable;
};

}  // namespace emergent::force

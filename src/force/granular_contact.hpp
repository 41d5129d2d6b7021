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

// SPDX-License-Identifier: MIT
// Granular contacts as a law of the neighbour loop (neighbour_loop.hpp): spheres within
// range_factor times their mean diameter meet with the contact law of their species pair
// (contact_force). Its force is exactly antisymmetric (every term flips sign exactly with the
// normal and the relative velocity), so on the full list a pair's two sides agree bit for bit.
#pragma once

#include <cmath>

#include "force/granular_contact.hpp"
#include "emergent/neighbour_loop.hpp"

namespace emergent::force {

/// The laws by species pair as the host reads them (any number of species).
struct HostContactPairs {
    const GranularPair* pair;
    EMERGENT_HD const GranularPair& operator[](int k) const { return pair[k]; }
};

/// `Table`: HostContactPairs, or ContactTable (by value, up to kContactTableSpecies species,
/// so a device kernel holds its own copy).
template <class Features, class Table>
struct ContactLaw {
    static constexpr unsigned needs = kNeedsDiameter |
                                      (Features::damping || Features::friction ? unsigned(kNeedsVelocity) : 0u) |
                                      (Features::species_table ? unsigned(kNeedsSpecies) : 0u);
    Table table;
    int n_species;
    Real half_range;  ///< r_c = half_range (d_i + d_j)

    /// Most listed pairs lie beyond contact: their velocities and species are never read.
    EMERGENT_HD bool in_range(const PairMember& i, const PairMember& j, const Vec3& r) const {
        const Real rc = half_range * (i.diameter + j.diameter);
        return dot(r, r) < rc * rc;
    }

    template <class List, bool Sample>
    EMERGENT_HD bool pair(const PairMember& i, const PairMember& j, const Vec3& r, PairTerm& t) const {
        const Real r2 = dot(r, r), rc = half_range * (i.diameter + j.diameter);
        if (r2 >= rc * rc) return false;
        const Real dist = std::sqrt(r2);
        const GranularPair& p = table[Features::species_table ? i.species * n_species + j.species : 0];
        t.f = contact_force<Features::damping, Features::friction>((1 / dist) * r, rc - dist, i.v - j.v, p);
        if constexpr (Sample) {
            // In units of the pair's mean diameter.
            t.overlap = (rc - dist) / (0.5 * (i.diameter + j.diameter));
            t.energy = 0.5 * p.k_n * (rc - dist) * (rc - dist);
            t.virial = dot(r, t.f);
        }
        return true;
    }
};

}  // namespace emergent::force

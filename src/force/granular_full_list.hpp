// SPDX-License-Identifier: MIT
// Granular contacts over the full neighbour list as a per-particle functor: each particle sums
// the contact forces on itself and writes nothing else, so the loop runs as CPU code or one GPU
// thread per particle without atomics. The contact law is the half list's (contact_force), and
// its force is exactly antisymmetric (every term flips sign exactly with the normal and the
// relative velocity), so the pair's two sides agree bit for bit.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "force/granular_contact.hpp"

namespace emergent::force {

template <class Features>
struct ContactForceFullList {
    const Vec3* x;
    const Vec3* v;
    const Real* diameter;
    const int* species;
    Vec3* f;
    const std::uint32_t* offset;
    const std::uint32_t* index;
    ContactTable table;  ///< by value
    int n_species;
    Real half_range;  ///< r_c = half_range (d_i + d_j)
    // Sampling steps: half of each contact's energy and r.f, and the largest overlap per
    // particle (in units of the pair's mean diameter; 0 without contacts).
    Real* energy = nullptr;
    Real* virial = nullptr;
    Real* overlap = nullptr;

    EMERGENT_HD void operator()(std::size_t i) const {
        const Vec3 xi = x[i], vi = v[i];
        const Real di = diameter[i];
        Vec3 fi{0, 0, 0};
        Real e = 0, w = 0, worst = 0;
        for (std::uint32_t k = offset[i]; k < offset[i + 1]; ++k) {
            const std::uint32_t j = index[k];
            const Vec3 r = xi - x[j];
            const Real r2 = dot(r, r), rc = half_range * (di + diameter[j]);
            if (r2 >= rc * rc) continue;
            const Real dist = std::sqrt(r2);
            const GranularPair& p =
                Features::species_table ? table.pair[species[i] * n_species + species[j]] : table.pair[0];
            const Vec3 fij = contact_force<Features::damping, Features::friction>(
                (1 / dist) * r, rc - dist, vi - v[j], p);
            fi += fij;
            if constexpr (Features::sample) {
                const Real o = (rc - dist) / (0.5 * (di + diameter[j]));
                worst = o > worst ? o : worst;
                e += 0.5 * p.k_n * (rc - dist) * (rc - dist);
                w += dot(r, fij);
            }
        }
        f[i] += fi;
        if constexpr (Features::sample) {
            energy[i] = 0.5 * e;
            virial[i] = 0.5 * w;
            overlap[i] = worst;
        }
    }
};

}  // namespace emergent::force

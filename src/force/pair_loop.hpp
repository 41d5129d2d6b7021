// SPDX-License-Identifier: MIT
// CPU loop over a half neighbour list, applying any pair evaluator.
#pragma once

#include <algorithm>

#include "emergent/force_term.hpp"
#include "neighbour/neighbour_list.hpp"

namespace emergent::force {

/// Compile-time switches of the pair loop; each combination is its own instantiation, so the
/// force-only path carries no energy or virial arithmetic. The generic features exist to
/// measure what specialisation saves (benchmarks/specialisation_cost.sh): a species table (one
/// evaluator per species pair) and pairwise damping -gamma (v_ij . r_ij) r_ij / r^2.
template <bool Sample, bool SpeciesTable = false, bool Damping = false>
struct PairFeatures {
    static constexpr bool sample = Sample, species_table = SpeciesTable, damping = Damping;
};

/// What the generic features read: evaluators per species pair (row-major, n_species^2) and
/// the damping coefficient.
template <class Evaluator>
struct PairTable {
    const Evaluator* pairs = nullptr;
    int n_species = 1;
    Real gamma = 0;
};

/// Adds pair forces for every listed pair (Newton's third law on both members; forces landing on
/// ghosts are discarded by the caller's next zeroing). Energy and virial of an owned–ghost pair
/// count half here: the rank that owns the ghost counts the other half.
/// Only the rows [first, last) of the list are visited (ForceContext).
template <class Features, class Evaluator>
void pair_forces_half_list(ParticleStore& store, const NeighbourList& list, const Evaluator& eval0,
                           ForceSums& sums, const ForceContext& rows,
                           const PairTable<Evaluator>& table = {}) {
    const std::size_t n_owned = list.n_owned();
    const std::size_t last = std::min(rows.last, n_owned);
    const Vec3* x = store.position.data();
    const Vec3* v = store.velocity.data();
    const int* sp = store.species.data();
    Vec3* f = store.force.data();
    const std::uint32_t* offset = list.offsets();
    const std::uint32_t* nb = list.neighbours();
    double potential = 0, virial = 0;
    for (std::size_t i = rows.first; i < last; ++i) {
        const Vec3 xi = x[i];
        Vec3 fi{0, 0, 0};
        for (std::uint32_t k = offset[i]; k < offset[i + 1]; ++k) {
            const std::uint32_t j = nb[k];
            const Evaluator& eval =
                Features::species_table ? table.pairs[sp[i] * table.n_species + sp[j]] : eval0;
            const Real dx = xi.x - x[j].x, dy = xi.y - x[j].y, dz = xi.z - x[j].z;
            const Real r2 = dx * dx + dy * dy + dz * dz;
            // Branch-free: about half the listed pairs lie beyond the cutoff, at random, so a
            // branch would mispredict often; a masked multiply costs less than that.
            const Real inside = r2 < eval.cutoff_sq ? Real(1) : Real(0);
            Real fr = inside * eval.force_over_r(r2);
            if constexpr (Features::damping) {
                const Vec3 dv = v[i] - v[j];
                fr -= inside * table.gamma * (dv.x * dx + dv.y * dy + dv.z * dz) / r2;
            }
            fi.x += fr * dx;
            fi.y += fr * dy;
            fi.z += fr * dz;
            f[j].x -= fr * dx;
            f[j].y -= fr * dy;
            f[j].z -= fr * dz;
            if constexpr (Features::sample) {
                const Real weight = j < n_owned ? 1.0 : 0.5;
                potential += inside * weight * eval.energy(r2);
                virial += weight * fr * r2;
            }
        }
        f[i] += fi;
    }
    if constexpr (Features::sample) {
        sums.potential += potential;
        sums.virial += virial;
    }
}

}  // namespace emergent::force

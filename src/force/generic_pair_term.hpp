// SPDX-License-Identifier: MIT
// A radial law with every feature of a pair law compiled in and evaluated (a species table,
// pairwise damping, velocities and species read, energy and virial every step): the same forces
// as its specialised term (emergent/pair_law.hpp), to measure what specialisation saves
// (benchmarks/specialisation_cost.sh). Host half list only.
#pragma once

#include "emergent/pair_law.hpp"

namespace emergent::force {

/// An evaluator per species pair (row-major, n_species^2) and pairwise damping
/// -gamma (v_ij . r_ij) r_ij / r^2.
template <class Evaluator>
struct TabulatedDampedLaw {
    static constexpr unsigned needs = kNeedsVelocity | kNeedsSpecies;
    const Evaluator* pairs = nullptr;
    int n_species = 1;
    Real gamma = 0;

    template <class List, bool Sample>
    bool pair(const PairMember& i, const PairMember& j, const Vec3& d, PairTerm& t) const {
        static_assert(List::kHost, "the generic law runs on the host's half list");
        const Evaluator& eval = pairs[i.species * n_species + j.species];
        const Real dx = d.x, dy = d.y, dz = d.z;
        const Real r2 = dx * dx + dy * dy + dz * dz;
        const Real inside = r2 < eval.cutoff_sq ? Real(1) : Real(0);
        Real fr = inside * eval.force_over_r(r2);
        const Vec3 dv = i.v - j.v;
        fr -= inside * gamma * (dv.x * dx + dv.y * dy + dv.z * dz) / r2;
        t.f = {fr * dx, fr * dy, fr * dz};
        if constexpr (Sample) {
            t.energy = inside * eval.energy(r2);
            t.virial = fr * r2;
        }
        return true;
    }
};

/// The radial term run through TabulatedDampedLaw (one species, gamma 0).
template <class Evaluator>
class GenericPairTerm final : public RadialPairTerm<Evaluator> {
public:
    using RadialPairTerm<Evaluator>::RadialPairTerm;
    std::string name() const override { return RadialPairTerm<Evaluator>::name() + "-generic"; }
    unsigned ghost_fields() const override { return kPosition | kVelocity | kSpecies; }
    bool on_backend() const override { return false; }
    bool stores_on_backend() const override { return false; }

    void add_forces(ParticleStore& store, const NeighbourList& list, const ForceContext& rows, bool,
                    ForceSums& sums) const override {
        const HalfListRows l = half_list_rows(list);
        const PairArrays a{store.position.data(), store.velocity.data(), nullptr, store.species.data(),
                           store.force.data(),    l.offset,              l.index};
        const PairSums s = pair_forces_half_list<true>(TabulatedDampedLaw<Evaluator>{&this->evaluator(), 1, 0.0}, a,
                                                       l.n_owned, rows.first, rows.last);
        sums.potential += s.energy;
        sums.virial += s.virial;
    }
};

}  // namespace emergent::force

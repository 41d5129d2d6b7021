// SPDX-License-Identifier: MIT
// A force term for any radial pair potential, given its evaluator (radial_pair_law.hpp): the
// host's half list and the back end's full list through the one neighbour loop. A new radial
// law is an evaluator and a factory that makes this term of it (docs/plugins.md, "A new pair
// law"; lennard_jones_term.cpp is the example).
#pragma once

#include <string>
#include <utility>

#include "emergent/execution.hpp"
#include "emergent/force_term.hpp"
#include "force/radial_pair_law.hpp"
#include "neighbour/neighbour_list.hpp"

namespace emergent::force {

template <class Evaluator>
class RadialPairTerm final : public ForceTerm {
public:
    /// `generic`: every feature of a pair law compiled in and evaluated, energy and virial every
    /// step (TabulatedDampedLaw; host only): for measuring what specialisation saves.
    RadialPairTerm(std::string name, const Evaluator& eval, double cutoff, bool generic)
        : name_(std::move(name)), law_{eval}, cutoff_(cutoff), generic_(generic) {}

    std::string name() const override { return generic_ ? name_ + "-generic" : name_; }
    double cutoff() const override { return cutoff_; }
    unsigned ghost_fields() const override { return generic_ ? kPosition | kVelocity | kSpecies : kPosition; }
    bool honours_range() const override { return true; }

    void add_forces(ParticleStore& store, const NeighbourList& list, const ForceContext& rows, bool sample,
                    ForceSums& sums) const override {
        const PairArrays a{store.position.data(), store.velocity.data(), nullptr, store.species.data(),
                           store.force.data(),    list.offsets(),        list.neighbours()};
        PairSums s;
        // The one place where the run-time flags become compile-time features.
        if (generic_)
            s = pair_forces_half_list<true>(TabulatedDampedLaw<Evaluator>{&law_.eval, 1, 0.0}, a, list.n_owned(),
                                            rows.first, rows.last);
        else if (sample)
            s = pair_forces_half_list<true>(law_, a, list.n_owned(), rows.first, rows.last);
        else
            s = pair_forces_half_list<false>(law_, a, list.n_owned(), rows.first, rows.last);
        if (generic_ || sample) {
            sums.potential += s.energy;
            sums.virial += s.virial;
        }
    }

    bool on_backend() const override { return !generic_; }
    bool stores_on_backend() const override { return true; }
    void add_forces_on_backend(const BackendParticles& p, const ForceContext& context, bool sample,
                               ForceSums& sums) const override {
        const PairArrays a{p.position, nullptr, nullptr, nullptr, p.force, p.list_offset, p.list_index};
        // Each owned particle's row is summed from zero, so replacing gives the bits adding to a
        // cleared force does.
        const bool accumulate = !context.replace_forces;
        if (!sample) {
            exec::for_each(p.target, p.n_owned,
                           PairForcesFullList<RadialPairLaw<Evaluator>, false>{law_, a, nullptr, nullptr, nullptr,
                                                                               accumulate});
            return;
        }
        exec::for_each(p.target, p.n_owned,
                       PairForcesFullList<RadialPairLaw<Evaluator>, true>{law_, a, p.energy, p.virial, nullptr,
                                                                          accumulate});
        // Each particle holds half of each of its pairs: an owned-ghost pair's other half is
        // counted by the rank that owns the ghost, as with the half list.
        sums.potential += exec::transform_sum<double>(p.target, p.n_owned, exec::ElementOf<Real>{p.energy});
        sums.virial += exec::transform_sum<double>(p.target, p.n_owned, exec::ElementOf<Real>{p.virial});
    }

private:
    std::string name_;
    RadialPairLaw<Evaluator> law_;
    double cutoff_;
    bool generic_;
};

}  // namespace emergent::force

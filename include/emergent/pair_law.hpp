// SPDX-License-Identifier: MIT
// A radial pair potential from its evaluator alone: the law the neighbour loop runs
// (neighbour_loop.hpp) and the force term that runs it on the host's half list and the back
// end's full list. A new law is one evaluator and one line making its term:
//   struct MyLaw { Real cutoff_sq; EMERGENT_HD Real force_over_r(Real r2) const;
//                  EMERGENT_HD Real energy(Real r2) const; };
//   sim.add_force(make_pair_term("my-law", MyLaw{...}, cutoff));
// in the evaluator's own arithmetic type (the member types of cutoff_sq). This header is all an
// out-of-tree plugin needs (docs/plugins.md, "A new pair law"). Compiled as CUDA the term's
// loops run on a GPU; compiled as plain C++ they run on the host back ends, and a device back
// end refuses them with a clear error (execution.hpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>

#include "emergent/execution.hpp"
#include "emergent/force_term.hpp"
#include "emergent/neighbour_loop.hpp"

namespace emergent {

/// The host's half list as the pair loop reads it: the owned particles' rows, i's neighbours at
/// index[offset[i] .. offset[i + 1]).
struct HalfListRows {
    std::size_t n_owned = 0;
    const std::uint32_t* offset = nullptr;
    const std::uint32_t* index = nullptr;
};
HalfListRows half_list_rows(const NeighbourList& list);

namespace force {

/// A radial potential as a law of the neighbour loop. On the host's half list every listed pair
/// is evaluated and masked beyond the cutoff (branch-free); on the full list the pairs beyond it
/// are skipped.
template <class Evaluator>
struct RadialPairLaw {
    static constexpr unsigned needs = 0;
    Evaluator eval;

    template <class List, bool Sample>
    EMERGENT_HD bool pair(const PairMember&, const PairMember&, const Vec3& d, PairTerm& t) const {
        using T = decltype(eval.cutoff_sq);
        const T dx = T(d.x), dy = T(d.y), dz = T(d.z);
        const T r2 = dx * dx + dy * dy + dz * dz;
        T fr, inside = T(1);
        if constexpr (List::kHost) {
            inside = r2 < eval.cutoff_sq ? T(1) : T(0);
            fr = inside * eval.force_over_r(r2);
        } else {
            if (!(r2 < eval.cutoff_sq)) return false;
            fr = eval.force_over_r(r2);
        }
        t.f = {Real(fr * dx), Real(fr * dy), Real(fr * dz)};
        if constexpr (Sample) {
            t.energy = List::kHost ? Real(inside * eval.energy(r2)) : Real(eval.energy(r2));
            t.virial = Real(fr * r2);
        }
        return true;
    }
};

/// The force term of a radial law: positions are all it reads and all its ghosts carry.
template <class Evaluator>
class RadialPairTerm : public ForceTerm {
public:
    RadialPairTerm(std::string name, const Evaluator& eval, double cutoff)
        : name_(std::move(name)), law_{eval}, cutoff_(cutoff) {}

    std::string name() const override { return name_; }
    double cutoff() const override { return cutoff_; }
    bool honours_range() const override { return true; }

    void add_forces(ParticleStore& store, const NeighbourList& list, const ForceContext& rows, bool sample,
                    ForceSums& sums) const override {
        const HalfListRows l = half_list_rows(list);
        const PairArrays a{store.position.data(), nullptr, nullptr, nullptr, store.force.data(), l.offset, l.index};
        if (!sample) {
            pair_forces_half_list<false>(law_, a, l.n_owned, rows.first, rows.last);
            return;
        }
        const PairSums s = pair_forces_half_list<true>(law_, a, l.n_owned, rows.first, rows.last);
        sums.potential += s.energy;
        sums.virial += s.virial;
    }

    bool on_backend() const override { return true; }
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

protected:
    const Evaluator& evaluator() const { return law_.eval; }

private:
    std::string name_;
    RadialPairLaw<Evaluator> law_;
    double cutoff_;
};

}  // namespace force

/// The force term of the radial law `eval`, listed to `cutoff` (the distance where its force
/// ends: sqrt(eval.cutoff_sq)), reported as `name`.
template <class Evaluator>
std::unique_ptr<ForceTerm> make_pair_term(std::string name, const Evaluator& eval, double cutoff) {
    return std::make_unique<force::RadialPairTerm<Evaluator>>(std::move(name), eval, cutoff);
}

}  // namespace emergent

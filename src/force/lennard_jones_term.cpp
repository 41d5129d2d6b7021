// SPDX-License-Identifier: MIT
// The Lennard-Jones force term.
#include <sstream>

#include "emergent/error.hpp"
#include "emergent/execution.hpp"
#include "force/lennard_jones.hpp"
#include "force/pair_full_list.hpp"
#include "force/pair_loop.hpp"

namespace emergent {

namespace {

class LennardJonesTerm final : public ForceTerm {
public:
    LennardJonesTerm(const force::LennardJones::Params& p, bool generic)
        : params_(p), eval_(p), generic_(generic), table_{&eval_, 1, 0.0} {}

    std::string name() const override { return generic_ ? "lennard-jones-generic" : "lennard-jones"; }
    double cutoff() const override { return params_.cutoff; }
    unsigned ghost_fields() const override {
        return generic_ ? kPosition | kVelocity | kSpecies : kPosition;
    }

    void add_forces(ParticleStore& store, const NeighbourList& list, const ForceContext& rows,
                    bool sample, ForceSums& sums) const override {
        // The one place where the run-time flag becomes a compile-time feature.
        if (generic_)  // everything compiled in and evaluated, energy and virial every step
            force::pair_forces_half_list<force::PairFeatures<true, true, true>>(store, list, eval_,
                                                                               sums, rows, table_);
        else if (sample)
            force::pair_forces_half_list<force::PairFeatures<true>>(store, list, eval_, sums, rows);
        else
            force::pair_forces_half_list<force::PairFeatures<false>>(store, list, eval_, sums, rows);
    }
    bool honours_range() const override { return true; }

    bool on_backend() const override { return !generic_; }
    bool stores_on_backend() const override { return true; }
    void add_forces_on_backend(const BackendParticles& p, const ForceContext& context, bool sample,
                               ForceSums& sums) const override {
        const force::CompressedNeighbours list{p.list_offset, p.list_index};
        // Each owned particle's row is summed from zero, so replacing gives the bits adding to
        // a cleared force does (0 + s = s: a sum started at +0 is never -0).
        const bool accumulate = !context.replace_forces;
        if (!sample) {
            exec::for_each(p.target, p.n_owned,
                           force::PairForceFullList<force::LennardJones>{
                               p.position, p.force, list, eval_, {}, nullptr, nullptr, accumulate});
            return;
        }
        exec::for_each(p.target, p.n_owned,
                       force::PairForceFullList<force::LennardJones, force::CompressedNeighbours,
                                                force::DirectSeparation, true>{
                           p.position, p.force, list, eval_, {}, p.energy, p.virial, accumulate});
        // Each particle holds half of each of its pairs: an owned-ghost pair's other half is
        // counted by the rank that owns the ghost, as with the half list.
        sums.potential += exec::transform_sum<double>(p.target, p.n_owned, exec::ElementOf<Real>{p.energy});
        sums.virial += exec::transform_sum<double>(p.target, p.n_owned, exec::ElementOf<Real>{p.virial});
    }

private:
    force::LennardJones::Params params_;
    force::LennardJones eval_;
    bool generic_;
    force::PairTable<force::LennardJones> table_;
};

}  // namespace

std::unique_ptr<ForceTerm> make_lennard_jones(double epsilon, double sigma, double cutoff,
                                              bool generic) {
    if (!(epsilon > 0) || !(sigma > 0) || !(cutoff > 0)) {
        std::ostringstream msg;
        msg << "lennard-jones: epsilon=" << epsilon << ", sigma=" << sigma << ", cutoff=" << cutoff
            << " must all be > 0";
        throw InputError(msg.str());
    }
    return std::make_unique<LennardJonesTerm>(force::LennardJones::Params{epsilon, sigma, cutoff},
                                              generic);
}

}  // namespace emergent

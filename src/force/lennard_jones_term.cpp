// SPDX-License-Identifier: MIT
// The Lennard-Jones force term.
#include <sstream>

#include "emergent/error.hpp"
#include "force/lennard_jones.hpp"
#include "force/pair_loop.hpp"

namespace emergent {

namespace {

class LennardJonesTerm final : public ForceTerm {
public:
    explicit LennardJonesTerm(const force::LennardJones::Params& p) : params_(p), eval_(p) {}

    std::string name() const override { return "lennard-jones"; }
    double cutoff() const override { return params_.cutoff; }

    void add_forces(ParticleStore& store, const NeighbourList& list, const ForceContext&,
                    bool sample, ForceSums& sums) const override {
        // The one place where the run-time flag becomes a compile-time feature.
        if (sample)
            force::pair_forces_half_list<force::PairFeatures<true>>(store, list, eval_, sums);
        else
            force::pair_forces_half_list<force::PairFeatures<false>>(store, list, eval_, sums);
    }

private:
    force::LennardJones::Params params_;
    force::LennardJones eval_;
};

}  // namespace

std::unique_ptr<ForceTerm> make_lennard_jones(double epsilon, double sigma, double cutoff) {
    if (!(epsilon > 0) || !(sigma > 0) || !(cutoff > 0)) {
        std::ostringstream msg;
        msg << "lennard-jones: epsilon=" << epsilon << ", sigma=" << sigma << ", cutoff=" << cutoff
            << " must all be > 0";
        throw InputError(msg.str());
    }
    return std::make_unique<LennardJonesTerm>(force::LennardJones::Params{epsilon, sigma, cutoff});
}

}  // namespace emergent

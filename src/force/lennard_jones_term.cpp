// SPDX-License-Identifier: MIT
// The Lennard-Jones force term: its evaluator (lennard_jones.hpp) in the radial pair term.
#include <memory>
#include <sstream>

#include "emergent/error.hpp"
#include "force/lennard_jones.hpp"
#include "force/radial_pair_term.hpp"

namespace emergent {

std::unique_ptr<ForceTerm> make_lennard_jones(double epsilon, double sigma, double cutoff, bool generic) {
    if (!(epsilon > 0) || !(sigma > 0) || !(cutoff > 0)) {
        std::ostringstream msg;
        msg << "lennard-jones: epsilon=" << epsilon << ", sigma=" << sigma << ", cutoff=" << cutoff
            << " must all be > 0";
        throw InputError(msg.str());
    }
    const force::LennardJones eval(force::LennardJones::Params{epsilon, sigma, cutoff});
    return std::make_unique<force::RadialPairTerm<force::LennardJones>>("lennard-jones", eval, cutoff, generic);
}

}  // namespace emergent

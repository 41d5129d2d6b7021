// SPDX-License-Identifier: MIT
// The Lennard-Jones force term: its evaluator (lennard_jones.hpp) in the radial pair term
// (emergent/pair_law.hpp), or in the generic one for benchmarks.
#include <memory>
#include <sstream>

#include "emergent/error.hpp"
#include "force/lennard_jones.hpp"
#include "force/generic_pair_term.hpp"

namespace emergent {

std::unique_ptr<ForceTerm> make_lennard_jones(double epsilon, double sigma, double cutoff, bool generic) {
    if (!(epsilon > 0) || !(sigma > 0) || !(cutoff > 0)) {
        std::ostringstream msg;
        msg << "lennard-jones: epsilon=" << epsilon << ", sigma=" << sigma << ", cutoff=" << cutoff
            << " must all be > 0";
        throw InputError(msg.str());
    }
    const force::LennardJones eval(force::LennardJones::Params{epsilon, sigma, cutoff});
    if (generic) return std::make_unique<force::GenericPairTerm<force::LennardJones>>("lennard-jones", eval, cutoff);
    return make_pair_term("lennard-jones", eval, cutoff);
}

}  // namespace emergent

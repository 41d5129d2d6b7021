// SPDX-License-Identifier: MIT
// What every force term has unless it says otherwise, and the list as pair terms read it.
#include <stdexcept>

#include "emergent/force_term.hpp"
#include "emergent/pair_law.hpp"
#include "neighbour/neighbour_list.hpp"

namespace emergent {

void ForceTerm::add_forces_on_backend(const BackendParticles&, const ForceContext&, bool,
                                      ForceSums&) const {
    // The engine asks only terms whose on_backend() is true.
    throw std::logic_error("force term '" + name() + "' has no back-end form");
}

HalfListRows half_list_rows(const NeighbourList& list) {
    return HalfListRows{list.n_owned(), list.offsets(), list.neighbours()};
}

}  // namespace emergent

// SPDX-License-Identifier: MIT
// What every force term has unless it says otherwise.
#include <stdexcept>

#include "emergent/force_term.hpp"

namespace emergent {

void ForceTerm::add_forces_on_backend(const BackendParticles&, const ForceContext&, bool,
                                      ForceSums&) const {
    // The engine asks only terms whose on_backend() is true.
    throw std::logic_error("force term '" + name() + "' has no back-end form");
}

}  // namespace emergent

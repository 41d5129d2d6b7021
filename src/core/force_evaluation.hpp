// SPDX-License-Identifier: MIT
// The forces of a step: every force term over the neighbour list, in their back-end form (full
// list, the particles where they live) or their host form (half list, overlapping the ghosts'
// refresh where the run asks), then the bodies' sums of their spheres' forces.
#pragma once
#include <memory>
#include <vector>

#include "core/engine_state.hpp"
#include "core/neighbourhood.hpp"
#include "emergent/backend_particles.hpp"
#include "emergent/force_term.hpp"

namespace emergent {

class ForceEvaluation {
public:
    ForceEvaluation(EngineState& state, Neighbourhood& neighbourhood) : s_(state), near_(neighbourhood) {}

    void add(std::unique_ptr<ForceTerm> term);
    const std::vector<std::unique_ptr<ForceTerm>>& terms() const { return terms_; }
    /// The longest cutoff of the terms.
    double cutoff() const;
    bool conservative() const;

    /// Forces at the current positions, which are those of time `at` (walls that move with time
    /// are placed there); `sample`: the terms sum energy and virial too.
    void compute(bool sample, double at);
    /// The sums of the last sampled evaluation.
    const ForceSums& sums() const { return sums_; }

    /// The particles and the full list as the back end's loops see them.
    BackendParticles backend_particles();

private:
    void compute_on_backend(bool sample, double at);
    void compute_on_host(bool sample, double at);
    /// The first (pair) term's interior rows while the ghosts arrive, then the rest.
    void compute_overlapping_refresh(const ForceContext& context, bool sample);

    EngineState& s_;
    Neighbourhood& near_;
    std::vector<std::unique_ptr<ForceTerm>> terms_;
    ForceSums sums_;
    std::vector<Real> energy_scratch_, virial_scratch_, overlap_scratch_;  ///< host back end's sums
    unsigned long long ghosts_cleared_at_ = 0;  ///< the build after which the ghosts' forces were zeroed
};

}  // namespace emergent

// SPDX-License-Identifier: MIT
// Lennard-Jones pair interaction, truncated and shifted: the evaluator used on CPU and GPU.
#pragma once

#include "emergent/vec3.hpp"

namespace emergent::force {

/// u(r) = 4 eps [(s/r)^12 - (s/r)^6] - u(rc) for r < rc. Evaluated from r^2 to avoid sqrt.
struct LennardJones {
    struct Params {
        Real epsilon = 1, sigma = 1, cutoff = 1.122462048309373;
    };

    Real c12 = 0, c6 = 0, cutoff_sq = 0, shift = 0;

    LennardJones() = default;
    explicit LennardJones(const Params& p) {
        const Real s6 = p.sigma * p.sigma * p.sigma * p.sigma * p.sigma * p.sigma;
        c12 = 4 * p.epsilon * s6 * s6;
        c6 = 4 * p.epsilon * s6;
        cutoff_sq = p.cutoff * p.cutoff;
        const Real ri6 = 1 / (cutoff_sq * cutoff_sq * cutoff_sq);
        shift = ri6 * (c12 * ri6 - c6);
    }

    /// |f| / r for a pair at squared distance r2 (< cutoff_sq): f_vec = force_over_r * r_vec.
    EMERGENT_HD Real force_over_r(Real r2) const {
        const Real ri2 = 1 / r2;
        const Real ri6 = ri2 * ri2 * ri2;
        return ri6 * (12 * c12 * ri6 - 6 * c6) * ri2;
    }

    /// Shifted pair energy at squared distance r2 (< cutoff_sq).
    EMERGENT_HD Real energy(Real r2) const {
        const Real ri2 = 1 / r2;
        const Real ri6 = ri2 * ri2 * ri2;
        return ri6 * (c12 * ri6 - c6) - shift;
    }
};

}  // namespace emergent::force

// SPDX-License-Identifier: MIT
// Lennard-Jones pair interaction, truncated and shifted: the evaluator used on CPU and GPU.
#pragma once

#include "emergent/vec3.hpp"

namespace emergent::force {

/// Parameters of the Lennard-Jones pair term.
struct LennardJonesParams {
    Real epsilon = 1, sigma = 1, cutoff = 1.122462048309373;
};

/// u(r) = 4 eps [(s/r)^12 - (s/r)^6] - u(rc) for r < rc. Evaluated from r^2 to avoid sqrt.
/// T is the arithmetic type: double is the reference; float is the GPU's mixed mode, whose
/// coefficients are rounded once here (see as<float>()), not at every pair.
template <class T>
struct LennardJonesT {
    using Params = LennardJonesParams;

    T c12 = 0, c6 = 0, cutoff_sq = 0, shift = 0;

    LennardJonesT() = default;
    explicit LennardJonesT(const Params& p) {
        const double s6 = p.sigma * p.sigma * p.sigma * p.sigma * p.sigma * p.sigma;
        const double c12d = 4 * p.epsilon * s6 * s6, c6d = 4 * p.epsilon * s6;
        const double rc2 = p.cutoff * p.cutoff;
        const double ri6 = 1 / (rc2 * rc2 * rc2);
        c12 = T(c12d);
        c6 = T(c6d);
        cutoff_sq = T(rc2);
        shift = T(ri6 * (c12d * ri6 - c6d));
    }

    /// The same interaction evaluated in another arithmetic type.
    template <class U>
    LennardJonesT<U> as() const {
        LennardJonesT<U> o;
        o.c12 = U(c12);
        o.c6 = U(c6);
        o.cutoff_sq = U(cutoff_sq);
        o.shift = U(shift);
        return o;
    }

    /// |f| / r for a pair at squared distance r2 (< cutoff_sq): f_vec = force_over_r * r_vec.
    EMERGENT_HD T force_over_r(T r2) const {
        const T ri2 = T(1) / r2;
        const T ri6 = ri2 * ri2 * ri2;
        return ri6 * (T(12) * c12 * ri6 - T(6) * c6) * ri2;
    }

    /// Shifted pair energy at squared distance r2 (< cutoff_sq).
    EMERGENT_HD T energy(T r2) const {
        const T ri2 = T(1) / r2;
        const T ri6 = ri2 * ri2 * ri2;
        return ri6 * (c12 * ri6 - c6) - shift;
    }
};

using LennardJones = LennardJonesT<Real>;

}  // namespace emergent::force

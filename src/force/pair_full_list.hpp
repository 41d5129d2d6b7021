// SPDX-License-Identifier: MIT
// Pair forces over a full neighbour list as a per-particle functor: the same code runs as a
// CPU loop (exec::Host) and as one CUDA thread per particle (exec::Cuda), without atomics.
#pragma once

#include <cstdint>

#include "emergent/vec3.hpp"

namespace emergent::force {

/// f[i] = sum over listed j of the evaluator's pair force; writes only f[i].
template <class Evaluator>
struct PairForceFullList {
    const Vec3* x;
    Vec3* f;
    const std::uint32_t* offset;
    const std::uint32_t* neighbour;
    Evaluator eval;

    EMERGENT_HD void operator()(std::size_t i) const {
        const Vec3 xi = x[i];
        Vec3 fi{0, 0, 0};
        for (std::uint32_t k = offset[i]; k < offset[i + 1]; ++k) {
            const Vec3 xj = x[neighbour[k]];
            const Real dx = xi.x - xj.x, dy = xi.y - xj.y, dz = xi.z - xj.z;
            const Real r2 = dx * dx + dy * dy + dz * dz;
            const Real fr = r2 < eval.cutoff_sq ? eval.force_over_r(r2) : Real(0);
            fi.x += fr * dx;
            fi.y += fr * dy;
            fi.z += fr * dz;
        }
        f[i] = fi;
    }
};

}  // namespace emergent::force

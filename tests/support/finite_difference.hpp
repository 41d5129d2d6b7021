// SPDX-License-Identifier: MIT
// Central finite differences of an energy, the reference a conservative force is checked against.
#pragma once

#include "emergent/vec3.hpp"

namespace emergent::fixtures {

/// -grad E at x by central differences of step h along each axis. Its error is the truncation
/// h^2 |E'''| / 6 plus the round-off ~ eps |E| / h, so h is chosen per law between the two.
template <class Energy>
Vec3 minus_gradient(const Energy& energy, const Vec3& x, double h) {
    Vec3 f{0, 0, 0};
    for (int d = 0; d < 3; ++d) {
        Vec3 up = x, down = x;
        up[d] += h;
        down[d] -= h;
        f[d] = -(energy(up) - energy(down)) / (2 * h);
    }
    return f;
}

}  // namespace emergent::fixtures

// SPDX-License-Identifier: MIT
// The Lennard-Jones evaluator against its closed form.
#include <gtest/gtest.h>

#include <cmath>

#include "force/lennard_jones.hpp"

using emergent::force::LennardJones;

TEST(LennardJones, EnergyIsShiftedToZeroAtCutoffAndMatchesClosedForm) {
    const LennardJones lj({1.5, 0.9, 2.5});
    const double rc = 2.5;
    EXPECT_NEAR(lj.energy(rc * rc), 0.0, 1e-15);
    const double r = 1.1, s = 0.9 / r, src = 0.9 / rc;
    const double expected = 4 * 1.5 * (std::pow(s, 12) - std::pow(s, 6)) -
                            4 * 1.5 * (std::pow(src, 12) - std::pow(src, 6));
    EXPECT_NEAR(lj.energy(r * r), expected, 1e-13);
}

TEST(LennardJones, ForceIsMinusEnergyDerivative) {
    const LennardJones lj({1.0, 1.0, std::pow(2.0, 1.0 / 6.0)});
    for (double r : {0.85, 0.95, 1.0, 1.05, 1.1}) {
        // Central difference: error O(h^2 u''') ~ 1e-8 at h = 1e-5; round-off ~ 1e-16/h ~ 1e-11.
        const double h = 1e-5;
        const double du = (lj.energy((r + h) * (r + h)) - lj.energy((r - h) * (r - h))) / (2 * h);
        EXPECT_NEAR(lj.force_over_r(r * r) * r, -du, 1e-6 * std::max(1.0, std::abs(du))) << r;
    }
    // WCA: the force vanishes at the minimum 2^(1/6).
    const double rm = std::pow(2.0, 1.0 / 6.0);
    EXPECT_NEAR(lj.force_over_r(rm * rm), 0.0, 1e-12);
}

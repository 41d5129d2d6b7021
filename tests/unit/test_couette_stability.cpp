// SPDX-License-Identifier: MIT
// Linear stability of circular Couette flow (outer cylinder at rest) against published
// critical points and against a second solution of the same equations.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "emergent/kit/couette_stability.hpp"

using namespace emergent;

namespace {
constexpr double kPi = 3.14159265358979323846;
}

// Published critical Reynolds numbers: eta = 0.5 and 0.95 from Recktenwald, Luecke & Mueller,
// Phys. Rev. E 48, 4444 (1993) (68.19, k_c = 3.16; 184.99, k_c = 3.13); 0.875 the classic
// 118.16 (e.g. Marcus, J. Fluid Mech. 146, 45, 1984). They are quoted to 0.01, which is the
// tolerance (the solver itself converges to ~1e-8 relative at 32 points).
TEST(CouetteStability, CriticalReynoldsMatchesPublishedValues) {
    const struct { double eta, re_c, k_c; } cases[] = {{0.5, 68.19, 3.16}, {0.875, 118.16, 3.13},
                                                      {0.95, 184.99, 3.13}};
    for (const auto& c : cases) {
        const CouetteStability::Onset onset = CouetteStability(c.eta).onset();
        EXPECT_NEAR(onset.reynolds, c.re_c, 0.01) << "eta " << c.eta;
        EXPECT_NEAR(onset.wavenumber, c.k_c, 0.005) << "eta " << c.eta;
    }
}

// The paper's two systems (r_i/r_o = 2/3 and 5/7): Re_c = 76.3 and 81.1, lambda_c = 2.00 d,
// quoted to 0.1 and 0.01 d.
TEST(CouetteStability, PaperSystemsOnset) {
    const CouetteStability::Onset small = CouetteStability(2.0 / 3.0).onset();
    EXPECT_NEAR(small.reynolds, 76.3, 0.05);
    EXPECT_NEAR(2 * kPi / small.wavenumber, 2.00, 0.005);
    const CouetteStability::Onset large = CouetteStability(5.0 / 7.0).onset();
    EXPECT_NEAR(large.reynolds, 81.1, 0.05);
    EXPECT_NEAR(2 * kPi / large.wavenumber, 2.00, 0.005);
}

// Growth rates against the generalized eigenvalues of the same collocation problem computed
// by the QZ algorithm (scipy.linalg.eig, 40 points; a different algorithm on a different
// grid), eta = 2/3 at Re = 86.5 and 108, k = m pi / 4; quoted to 1e-3.
TEST(CouetteStability, GrowthRatesMatchQzEigenvalues) {
    const CouetteStability s(2.0 / 3.0);
    const struct { double re; int m; double sigma; } cases[] = {
        {86.5, 4, 3.560}, {86.5, 5, 2.922}, {86.5, 6, -0.095}, {108, 4, 11.211}, {108, 5, 11.663},
        {108, 8, -1.720}, {65, 4, -3.881}};
    for (const auto& c : cases)
        EXPECT_NEAR(s.growth_rate(c.re, c.m * kPi / 4), c.sigma, 2e-3) << "Re " << c.re << " m " << c.m;
}

// The two routes to the neutral curve agree: the growth rate vanishes at the marginal
// Reynolds number, below it modes decay, above they grow.
TEST(CouetteStability, GrowthRateVanishesOnTheMarginalCurve) {
    const CouetteStability s(0.6);
    for (double k : {2.0, 3.1, 4.5}) {
        const double re = s.marginal_reynolds(k);
        EXPECT_NEAR(s.growth_rate(re, k), 0, 1e-6) << "k " << k;
        EXPECT_LT(s.growth_rate(0.95 * re, k), 0);
        EXPECT_GT(s.growth_rate(1.05 * re, k), 0);
    }
}

// Which mode a finite cylinder picks: at eta = 2/3 and L = 4 d with stress-free ends (k = m pi / 4),
// 4 vortices (k = pi, the critical wave) grow fastest just above onset, 5 at twice Ta_c
// (Re = 108, where the fastest growing wave of the infinite cylinder is ~1.72 d); periodic
// ends admit only even counts.
TEST(CouetteStability, FastestAdmissibleMode) {
    const CouetteStability s(2.0 / 3.0);
    EXPECT_EQ(s.fastest_admissible_mode(86.5, 4, false).vortices, 4);
    EXPECT_EQ(s.fastest_admissible_mode(108, 4, false).vortices, 5);
    const auto periodic = s.fastest_admissible_mode(108, 4, true);
    EXPECT_EQ(periodic.vortices % 2, 0);
    EXPECT_EQ(periodic.vortices, 4);
    EXPECT_NEAR(periodic.wavenumber, kPi, 1e-12);
}

// A long cylinder (hundreds of admissible modes) is searched near the maximum of sigma(k)
// instead of mode by mode: the same mode as the full scan, so a long run's set-up stays short.
TEST(CouetteStability, LongCylinderSearchFindsTheFullScansMode) {
    const CouetteStability s(2.0 / 3.0);
    for (const double re : {80.0, 108.0, 200.0}) {
        const double length = 40;  // gap widths: 4 * 40 * k_max / (4 k_c) = 160 modes
        const double step = kPi / length;
        int best = 0;
        double best_rate = 0;
        for (int m = 1; m * step <= 4 * s.onset().wavenumber; ++m) {
            const double r = s.growth_rate(re, m * step);
            if (best == 0 || r > best_rate) best = m, best_rate = r;
        }
        const auto found = s.fastest_admissible_mode(re, length, false);
        EXPECT_EQ(found.index, best) << "Re " << re;
        EXPECT_DOUBLE_EQ(found.growth_rate, best_rate) << "Re " << re;
    }
}

TEST(CouetteStability, RejectsRadiusRatioOutsideTheGap) {
    EXPECT_THROW(CouetteStability(1.0), std::invalid_argument);
    EXPECT_THROW(CouetteStability(0.0), std::invalid_argument);
}

// SPDX-License-Identifier: MIT
// A wall's start-up schedule: its speed factor, and the distance it has travelled, checked
// against numerical integration of that factor.
#include <gtest/gtest.h>

#include "boundary/wall_geometry.hpp"
#include "emergent/boundary.hpp"

using namespace emergent;

namespace {

/// Trapezoidal integral of the factor over [0, t]: exact for a piecewise-linear function
/// whose kinks fall on the grid, to round-off elsewhere (1e-6 of a step per kink at 1e6 points).
double integrate_factor(const WallMotion& m, double t) {
    const int n = 1000000;
    double sum = 0;
    for (int k = 0; k < n; ++k) sum += 0.5 * (m.factor(t * k / n) + m.factor(t * (k + 1) / n)) * t / n;
    return sum;
}

}  // namespace

TEST(WallMotion, WithoutStartUpItMovesAtFullSpeed) {
    WallMotion m;
    m.omega = 0.1;
    for (double t : {0.0, 1.0, 1e6}) {
        EXPECT_EQ(m.factor(t), 1.0);
        EXPECT_DOUBLE_EQ(m.travelled(t), t);
    }
}

TEST(WallMotion, StepAndRampFollowTheSchedule) {
    WallMotion m;
    m.omega = 0.1;
    m.start_factor = 0.7, m.start_until = 100, m.ramp = 50;
    EXPECT_EQ(m.factor(0), 0.7);
    EXPECT_EQ(m.factor(99.9), 0.7);
    EXPECT_DOUBLE_EQ(m.factor(125), 0.85);  // half way up the ramp
    EXPECT_EQ(m.factor(150), 1.0);
    EXPECT_EQ(m.factor(1e4), 1.0);
    // Travelled distance (in units of full speed) against the integral of the factor; the
    // tolerance is the quadrature's (kinks between grid points), far below the 0.1 % a wrong
    // branch of the closed form would give anywhere.
    for (double t : {37.0, 100.0, 112.5, 150.0, 333.0})
        EXPECT_NEAR(m.travelled(t), integrate_factor(m, t), 1e-6 * t) << "t = " << t;
}

TEST(WallMotion, SpinUpFromRestIsARamp) {
    WallMotion m;
    m.omega = 0.1;
    m.start_factor = 0, m.start_until = 0, m.ramp = 10;
    EXPECT_EQ(m.factor(0), 0.0);
    EXPECT_DOUBLE_EQ(m.factor(2.5), 0.25);
    EXPECT_DOUBLE_EQ(m.travelled(10), 5.0);  // half the distance at full speed
    for (double t : {3.0, 10.0, 20.0}) EXPECT_NEAR(m.travelled(t), integrate_factor(m, t), 1e-6 * t);
}

TEST(WallMotion, TheWallSurfaceCarriesTheFactor) {
    // A cylinder of radius 2 about z turning at omega = 0.5: surface speed 1 along +y at
    // (2, 0, 0), scaled by the factor of the moment.
    WallMotion m;
    m.omega = 0.5;
    m.start_factor = 0.2, m.start_until = 1, m.ramp = 0;
    const boundary::WallGeometry wall{WallShape::cylinder(2, {0, 0, 0}, 2.0, +1), m};
    const Vec3 early = wall.velocity_at({2, 0, 0}, 0.5), late = wall.velocity_at({2, 0, 0}, 1.5);
    EXPECT_NEAR(early.y, 0.2, 1e-15);
    EXPECT_NEAR(late.y, 1.0, 1e-15);
    EXPECT_NEAR(early.x, 0.0, 1e-15);
}

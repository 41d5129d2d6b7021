// SPDX-License-Identifier: MIT
// A thermal wall emits the velocities of a fluid at its temperature, for particles of any mass:
// an equilibrium flux leaving a wall at T has the flux-weighted Maxwell distribution
// p(v) ~ v_n exp(-m v^2 / 2 kT) (v_n > 0), so <v_t^2> = kT / m per tangential component and
// <v_n^2> = 2 kT / m, <v_n> = sqrt(pi kT / 2 m). Checked at two (T, m) pairs, neither 1.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "emergent/backend_particles.hpp"
#include "emergent/boundary.hpp"

using namespace emergent;

namespace {

/// Velocities with which n particles of mass m leave a thermal floor (z = 0, fluid above) at
/// temperature kT, run through the engine's rule (make_thermal_wall) as a step would run it.
/// The particles arrive as the flux of a fluid at T = 1, m = 1 (not the wall's): their
/// directions are spread as cos(theta) about the normal, as a fluid's are at any temperature,
/// and their speeds must not matter.
std::vector<Vec3> emitted(double kT, double m, int n, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u01(0, 1);
    std::normal_distribution<double> normal(0, 1);
    const double dt = 0.005;
    ParticleStore s;
    for (int i = 0; i < n; ++i) {
        const Vec3 v{normal(rng), normal(rng), -std::sqrt(-2 * std::log(1 - u01(rng)))};
        // Above the floor at the step's start, close enough to cross it during the drift.
        const Vec3 start{20 * u01(rng), 20 * u01(rng), -v.z * dt * u01(rng)};
        s.add_owned(start + dt * v, v, 0, i);
    }
    const std::vector<double> mass{m};
    const BackendParticles p = host_view(s, mass);
    const auto wall = make_thermal_wall(WallShape::plane(2, 0.0, +1), kT, seed);
    BoundaryContext context;
    context.dt = dt;
    context.step = 17;
    std::string fault;
    wall->apply(p, context, fault);
    EXPECT_TRUE(fault.empty()) << fault;
    EXPECT_EQ(wall->exchange().hits, n);
    return std::vector<Vec3>(s.velocity.begin(), s.velocity.begin() + n);
}

/// Mean of f over the samples and its standard error.
template <class F>
std::pair<double, double> mean_and_error(const std::vector<Vec3>& v, F f) {
    double sum = 0, sum2 = 0;
    for (const Vec3& w : v) {
        const double x = f(w);
        sum += x, sum2 += x * x;
    }
    const double n = double(v.size()), mean = sum / n;
    return {mean, std::sqrt((sum2 / n - mean * mean) / (n - 1))};
}

}  // namespace

TEST(ThermalWall, EmitsTheFluxOfAFluidAtItsTemperatureForAnyMass) {
    // 2e5 samples per pair: the standard error of <v_t^2> is sqrt(2 / n) kT / m = 0.3 %, and
    // the bound is 5 standard errors (a chance of 6e-7 per check for a correct wall; the
    // draws are seeded, so a pass is the same on every run). A wall that ignored the mass
    // (kT / m -> kT) is off by 150 % and 400 % here, one that emitted a plain Maxwellian
    // (not flux-weighted) has <v_n^2> = kT / m, off by 50 %.
    struct Case {
        double kT, m;
    };
    for (const Case c : {Case{2.5, 0.4}, Case{0.6, 3.0}}) {
        const std::vector<Vec3> v = emitted(c.kT, c.m, 200000, c.m < 1 ? 41 : 43);
        const double s2 = c.kT / c.m;  // the velocity scale squared
        const std::string where = "kT = " + std::to_string(c.kT) + ", m = " + std::to_string(c.m);
        int inward = 0;
        for (const Vec3& w : v) inward += w.z > 0;
        EXPECT_EQ(inward, int(v.size())) << where << ": every particle leaves into the fluid";
        const auto [vx2, ex] = mean_and_error(v, [](const Vec3& w) { return w.x * w.x; });
        const auto [vy2, ey] = mean_and_error(v, [](const Vec3& w) { return w.y * w.y; });
        const auto [vn2, en] = mean_and_error(v, [](const Vec3& w) { return w.z * w.z; });
        const auto [vn, e1] = mean_and_error(v, [](const Vec3& w) { return w.z; });
        const auto [vx, e0] = mean_and_error(v, [](const Vec3& w) { return w.x; });
        std::printf("%s: <vx^2> m/kT = %.4f, <vy^2> m/kT = %.4f, <vn^2> m/kT = %.4f, <vn> / "
                    "sqrt(kT/m) = %.4f\n",
                    where.c_str(), vx2 / s2, vy2 / s2, vn2 / s2, vn / std::sqrt(s2));
        EXPECT_NEAR(vx2, s2, 5 * ex) << where;
        EXPECT_NEAR(vy2, s2, 5 * ey) << where;
        EXPECT_NEAR(vn2, 2 * s2, 5 * en) << where;
        EXPECT_NEAR(vn, std::sqrt(M_PI * s2 / 2), 5 * e1) << where;
        EXPECT_NEAR(vx, 0.0, 5 * e0) << where << ": no drift along a wall at rest";
    }
}

TEST(ThermalWall, EmittedVelocitiesScaleExactlyAsTheSquareRootOfKTOverM) {
    // The same arrivals and draws at two (T, m): every emitted velocity is the other's times
    // sqrt((kT_2 / m_2) / (kT_1 / m_1)) (direction and random numbers do not depend on T or m),
    // to a few roundings.
    const std::vector<Vec3> a = emitted(2.5, 0.4, 20000, 53), b = emitted(0.6, 3.0, 20000, 53);
    const double ratio = std::sqrt((0.6 / 3.0) / (2.5 / 0.4));
    double worst = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const Vec3 d = b[i] - ratio * a[i];
        worst = std::max(worst, std::sqrt(dot(d, d) / dot(b[i], b[i])));
    }
    EXPECT_LT(worst, 1e-12);
}

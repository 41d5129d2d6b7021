// SPDX-License-Identifier: MIT
// Walls that have an energy: the force on a sphere is minus the gradient (central finite
// differences) of the elastic energy the wall reports on sampling steps, for the plane and
// smooth cylinder walls, the drum's rough wall and rough end cap, and the vibrating rod base
// (straight rods, rings, and its backing surface). Damping and friction are off (the
// conservative part); each wall is the force term the engine builds, run in its back-end form
// on the host, so the same per-particle functor as on a device.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "emergent/backend_particles.hpp"
#include "emergent/force_term.hpp"
#include "support/finite_difference.hpp"

using namespace emergent;

namespace {

constexpr double kRange = 1.122462048309373;  // 2^(1/6), the paper's contact range
const GranularPair kElastic{1000, 0, 0, 0};   // the paper's k_n; no damping, no friction
constexpr double kTwoPi = 6.283185307179586;

struct Probe {
    Vec3 force;
    double energy;
};

/// The force on one sphere (centre x, diameter d, at rest) from `term` at time t, and the
/// energy it reports; with sample false only the force (the run's ordinary steps).
Probe probe(const ForceTerm& term, const Vec3& x, double d, double t, bool sample = true) {
    ParticleStore s;
    s.enable_diameters();
    s.add_owned(x, {0, 0, 0}, 0, 0, d);
    s.force[0] = {0, 0, 0};
    const std::vector<double> mass{1.0};
    BackendParticles p = host_view(s, mass);
    Real energy = 0, virial = 0, overlap = 0;
    p.energy = &energy, p.virial = &virial, p.overlap = &overlap;
    ForceContext c;
    c.mass = &mass;
    c.time = t;
    ForceSums sums;
    term.add_forces_on_backend(p, c, sample, sums);
    return {s.force[0], sums.potential};
}

/// Checks the force at x against the energy's central differences; returns the energy there.
///
/// Why h = 1e-6 and 1e-6 max(1, |F|): each contact's energy is (k_n / 2) overlap^2 with the
/// overlap linear in the distance to a point, a line or an axis at least ~0.3 away, so
/// |U'''| <~ 3 k_n / 0.3 = 1e4 and the truncation h^2 |U'''| / 6 ~ 2e-9; the round-off
/// eps |U| / h is <~ 1e-8 for U <~ 50. A wrong factor or sign is an error of order |F| itself.
/// A contact's edge within h of x would add up to k_n h ~ 1e-3 (U'' jumps there): the points
/// are fixed (seeded), so a pass is not luck that could change from run to run.
double expect_conservative_at(const ForceTerm& term, const Vec3& x, double d, double t,
                              const std::string& where) {
    const Probe at = probe(term, x, d, t);
    const Vec3 fd = fixtures::minus_gradient(
        [&](const Vec3& y) { return probe(term, y, d, t).energy; }, x, 1e-6);
    const double tol = 1e-6 * std::max(1.0, std::sqrt(dot(at.force, at.force)));
    for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(at.force[k], fd[k], tol) << where << " at (" << x.x << ", " << x.y << ", "
                                             << x.z << "), axis " << k << ", U = " << at.energy;
    // Ordinary steps compute the same force without the energy.
    const Probe plain = probe(term, x, d, t, false);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(plain.force[k], at.force[k]) << where;
    return at.energy;
}

/// The sawtooth of the vibrated layer (test_rod_base.cpp's), teeth of both slopes.
RodBase sawtooth(bool rings, bool backing) {
    RodBase b;
    b.period = 13.5;
    b.vertices = {{0, 0}, {0.8 * 13.5, 3}, {13.5, 0}};
    b.rod_spacing = 0.5;
    b.rod_diameter = 0.2;
    b.rings = rings;
    b.amplitude = 1;
    b.frequency = 0.4;
    b.backing = backing;
    return b;
}

/// Height of that profile at u.
double profile(double u) {
    const double w = u - std::floor(u / 13.5) * 13.5, peak = 0.8 * 13.5;
    return w < peak ? 3 * w / peak : 3 * (13.5 - w) / (13.5 - peak);
}

}  // namespace

TEST(WallForceEnergy, PlaneWallsOnEitherSide) {
    const auto floor = make_plane_wall(2, 0.5, +1, kElastic, kRange);
    const auto side = make_plane_wall(0, 10, -1, kElastic, kRange);
    ASSERT_TRUE(floor->conservative());
    for (double gap : {0.05, 0.3, 0.5, 0.55}) {
        const double overlap = 0.5 * kRange * 1.1 - gap;  // d = 1.1
        const double u = expect_conservative_at(*floor, {1.3, 2.1, 0.5 + gap}, 1.1, 0, "floor");
        // And the energy is the spring's (k_n / 2) overlap^2 (relative round-off only).
        EXPECT_NEAR(u, 0.5 * kElastic.k_n * overlap * overlap, 1e-12 * kElastic.k_n) << gap;
        expect_conservative_at(*side, {10 - gap, 2.1, 0.7}, 1.1, 0, "side wall");
    }
    EXPECT_EQ(probe(*floor, {1.3, 2.1, 0.5 + 0.5 * kRange * 1.1 + 1e-9}, 1.1, 0).energy, 0.0);
}

TEST(WallForceEnergy, SmoothCylinderWall) {
    const auto wall = make_cylinder_wall(5, kElastic, kRange);
    ASSERT_TRUE(wall->conservative());
    int touching = 0;
    for (double gap : {0.1, 0.4, 0.55})
        for (double a : {0.7, 2.5, 4.0}) {
            const double r = 5 - gap;
            touching += expect_conservative_at(*wall, {r * std::cos(a), r * std::sin(a), 1.0}, 1.0,
                                               0, "cylinder") > 0;
        }
    EXPECT_EQ(touching, 9);
}

TEST(WallForceEnergy, RoughDrumWallSpheresAndTheSurfaceBehindThem) {
    RoughCylinder w;
    w.radius = 9.5, w.z_lo = 0, w.z_hi = 12, w.omega = 0.2, w.spacing = 2.2, w.sphere_diameter = 1;
    const auto wall = make_rough_cylinder_wall(w, kElastic, kRange);
    std::mt19937_64 rng(23);
    std::uniform_real_distribution<double> u01(0, 1);
    int touching = 0;
    for (int k = 0; k < 40; ++k) {
        // Spheres against the turning wall: many touch two or three wall spheres, some also
        // the smooth surface through their centres (gap below 0.56).
        const double a = kTwoPi * u01(rng), r = 9.5 - (0.1 + 0.8 * u01(rng)),
                     z = 1.5 + 9 * u01(rng);
        const double d = 0.8 + 0.4 * u01(rng), t = 10 * u01(rng);
        touching += expect_conservative_at(*wall, {r * std::cos(a), r * std::sin(a), z}, d, t,
                                           "rough drum wall") > 0;
    }
    EXPECT_GE(touching, 30);  // the check is not vacuous: most points are in contact
}

TEST(WallForceEnergy, RoughEndCap) {
    RoughEndCap cap;
    cap.z = 0.5, cap.radius = 6, cap.omega = 0.3, cap.spacing = 1.5, cap.sphere_diameter = 1;
    const auto wall = make_rough_end_cap(cap, kElastic, kRange);
    std::mt19937_64 rng(29);
    std::uniform_real_distribution<double> u01(0, 1);
    int touching = 0;
    for (int k = 0; k < 40; ++k) {
        const double a = kTwoPi * u01(rng), r = 5 * std::sqrt(u01(rng));
        const double z = 0.5 + 0.3 + 0.7 * u01(rng), t = 10 * u01(rng);
        touching += expect_conservative_at(*wall, {r * std::cos(a), r * std::sin(a), z}, 1.0, t,
                                           "rough end cap") > 0;
    }
    EXPECT_GE(touching, 30);
}

TEST(WallForceEnergy, RodBaseOfStraightRodsAndOfRings) {
    std::mt19937_64 rng(31);
    std::uniform_real_distribution<double> u01(0, 1);
    for (bool rings : {false, true}) {
        const RodBase b = sawtooth(rings, false);
        const auto base = make_rod_base(b, kElastic, kRange);
        ASSERT_FALSE(base->conservative());  // it moves; at a fixed time its force is conservative
        int touching = 0;
        for (int k = 0; k < 40; ++k) {
            const double u = 14 + 26 * u01(rng), t = 2.5 * u01(rng), a = kTwoPi * u01(rng);
            const double level = std::sin(kTwoPi * 0.4 * t);
            const double z = level + profile(u) + 0.3 + 0.45 * u01(rng);  // resting on rods
            const Vec3 x = rings ? Vec3{u * std::cos(a), u * std::sin(a), z} : Vec3{u, 3.7, z};
            touching +=
                expect_conservative_at(*base, x, 1.0, t, rings ? "rings" : "straight rods") > 0;
        }
        EXPECT_GE(touching, 30) << rings;
    }
}

TEST(WallForceEnergy, RodBaseBackingAboveAndBelowTheProfile) {
    std::mt19937_64 rng(37);
    std::uniform_real_distribution<double> u01(0, 1);
    const RodBase b = sawtooth(false, true);
    const auto base = make_rod_base(b, kElastic, kRange);
    const double peak = 0.8 * 13.5;
    int above = 0, below = 0;
    for (int k = 0; k < 60; ++k) {
        // Within a flank, at least 0.6 from its ends (the profile's vertices), so the nearest
        // point of the profile lies inside that flank. Not below a valley: there the nearest
        // point is the vertex, the energy grows with the distance to it, but the force pushes
        // along the nearest flank's normal, so it is not the energy's gradient (at 0.2 below
        // the valley F = (515, 0, -75), -grad U = (-51, 0, 177)); left out of this check.
        const bool gentle = k % 2 == 0;
        const double w =
            gentle ? 0.6 + (peak - 1.2) * u01(rng) : peak + 0.6 + (13.5 - peak - 1.2) * u01(rng);
        const double u = 13.5 * (1 + k % 3) + w, t = 2.5 * u01(rng);
        const double level = std::sin(kTwoPi * 0.4 * t);
        // Pressed between the rods (0.1 .. 0.5 above the profile, nearer to it than the
        // backing's reach 0.56) or pushed below it (0.05 .. 0.3 under it).
        const bool pressed = k % 4 < 2;
        const double dz = pressed ? 0.1 + 0.4 * u01(rng) : -(0.05 + 0.25 * u01(rng));
        const Vec3 x{u, 1.0, level + profile(u) + dz};
        const double e =
            expect_conservative_at(*base, x, 1.0, t, pressed ? "backing, above" : "backing, below");
        (pressed ? above : below) += e > 0;
    }
    EXPECT_EQ(above, 30);
    EXPECT_EQ(below, 30);
}

// SPDX-License-Identifier: MIT
// The vibrating rod base of the sawtooth scene: the index arithmetic that finds a sphere's rods
// misses none (against all of them), the mirrored base is the mirror image of the sawtooth in
// space, ring rods act in the plane normal to the ring, and the base carries its contacts with
// it as it moves.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "emergent/error.hpp"
#include "force/rod_base.hpp"

using namespace emergent;

namespace {

constexpr double kRange = 1.122462048309373;
const GranularPair kContact{1000, 5, 0, 0};

RodBase sawtooth(double gentle, bool mirrored, bool rings) {
    const double p = 13.5, h = 3;
    RodBase b;
    b.period = p;
    b.vertices = mirrored ? std::vector<std::pair<double, double>>{{0, 0}, {(1 - gentle) * p, h}, {p, 0}}
                          : std::vector<std::pair<double, double>>{{0, 0}, {gentle * p, h}, {p, 0}};
    b.rod_spacing = 0.5;
    b.rod_diameter = 0.2;
    b.rings = rings;
    b.amplitude = 1;
    b.frequency = 0.4;
    return b;
}

/// Reference for the index search: the contact law summed over every rod of the base listed
/// by rod_base_rods (in the (u, z) plane, the base raised by z_b(t)).
Vec3 all_rods_force(const RodBase& b, const Vec3& x, const Vec3& v, double d, double t, int& touching) {
    const double r = b.rings ? std::hypot(x.x, x.y) : x.x;
    const double cx = b.rings ? x.x / r : 1, cy = b.rings ? x.y / r : 0;
    const double w = 6.283185307179586 * b.frequency;
    const double level = b.amplitude * std::sin(w * t), speed = b.amplitude * w * std::cos(w * t);
    const double reach = 0.5 * kRange * (d + b.rod_diameter);
    Vec3 f{0, 0, 0};
    for (const auto& [u, z] : rod_base_rods(b, r - 2 * reach, r + 2 * reach)) {
        const double gu = r - u, gz = x.z - level - z, dist = std::hypot(gu, gz);
        if (dist >= reach) continue;
        ++touching;
        const Vec3 n{gu / dist * cx, gu / dist * cy, gz / dist};
        f += force::contact_force<true, false>(n, reach - dist, v - Vec3{0, 0, speed}, kContact);
    }
    return f;
}

}  // namespace

TEST(RodBase, IndexSearchFindsEveryRodInReach) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u01(0, 1);
    int touching = 0;
    for (bool rings : {false, true})
        for (double gentle : {0.5, 0.8, 1.0}) {
            const RodBase b = sawtooth(gentle, false, rings);
            const force::RodLattice l = force::rod_lattice(b);
            for (int k = 0; k < 4000; ++k) {
                // Points near and inside the teeth, at any time of the cycle.
                const double u = 0.5 + 40 * u01(rng), z = -1.5 + 6 * u01(rng), t = 10 * u01(rng);
                const double phi = 6.283185307179586 * u01(rng);
                const Vec3 x = rings ? Vec3{u * std::cos(phi), u * std::sin(phi), z} : Vec3{u, 3 * u01(rng), z};
                const Vec3 v{u01(rng) - 0.5, u01(rng) - 0.5, u01(rng) - 0.5};
                const double d = 0.9 + 0.6 * u01(rng);
                const Vec3 f = force::rod_base_force<true>(l, kContact, kRange, b.rod_diameter, x, v, d, t, nullptr);
                const Vec3 ref = all_rods_force(b, x, v, d, t, touching);
                for (int a = 0; a < 3; ++a)
                    ASSERT_NEAR(f[a], ref[a], 1e-9 * (1 + std::fabs(ref[a])))
                        << "rings " << rings << " gentle " << gentle << " at " << x.x << "," << x.y << "," << x.z;
            }
        }
    EXPECT_GT(touching, 10000);  // the points do meet the rods, many of them several at once
}

TEST(RodBase, MirroredBaseIsTheSawtoothReflectedInSpace) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u01(0, 1);
    int pushed = 0;
    for (double gentle : {0.7, 1.0}) {
        const force::RodLattice a = force::rod_lattice(sawtooth(gentle, false, false));
        const force::RodLattice m = force::rod_lattice(sawtooth(gentle, true, false));
        for (int k = 0; k < 2000; ++k) {
            const double u = 27 * u01(rng), z = -1 + 5 * u01(rng), t = 5 * u01(rng), d = 1 + 0.5 * u01(rng);
            const Vec3 v{u01(rng) - 0.5, u01(rng) - 0.5, u01(rng) - 0.5};
            const Vec3 f = force::rod_base_force<true>(a, kContact, kRange, 0.2, {u, 1, z}, v, d, t, nullptr);
            // The reflection u -> period - u (one period on: the same teeth) flips x and v_x.
            const Vec3 g = force::rod_base_force<true>(m, kContact, kRange, 0.2, {13.5 - u, 1, z},
                                                       {-v.x, v.y, v.z}, d, t, nullptr);
            // Rod positions come from different starting vertices: round-off apart.
            EXPECT_NEAR(g.x, -f.x, 1e-9 * (1 + std::fabs(f.x)));
            EXPECT_NEAR(g.y, f.y, 1e-12);
            EXPECT_NEAR(g.z, f.z, 1e-9 * (1 + std::fabs(f.z)));
            pushed += f.x != 0;
        }
    }
    EXPECT_GT(pushed, 500);  // the comparison sees sideways pushes, not only empty space
}

TEST(RodBase, RingsPushWithinTheirNormalPlaneAsStraightRodsDo) {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u01(0, 1);
    const force::RodLattice straight = force::rod_lattice(sawtooth(1.0, false, false));
    const force::RodLattice rings = force::rod_lattice(sawtooth(1.0, false, true));
    int pushed = 0;
    for (int k = 0; k < 2000; ++k) {
        const double r = 2 + 30 * u01(rng), z = -1 + 5 * u01(rng), phi = 6.283185307179586 * u01(rng);
        const double vr = u01(rng) - 0.5, vz = u01(rng) - 0.5, vphi = u01(rng) - 0.5;
        const Vec3 x{r * std::cos(phi), r * std::sin(phi), z};
        const Vec3 v{vr * std::cos(phi) - vphi * std::sin(phi), vr * std::sin(phi) + vphi * std::cos(phi), vz};
        const Vec3 f = force::rod_base_force<true>(rings, kContact, kRange, 0.2, x, v, 1.2, 0.7, nullptr);
        const Vec3 s = force::rod_base_force<true>(straight, kContact, kRange, 0.2, {r, 0, z}, {vr, vphi, vz}, 1.2,
                                                   0.7, nullptr);
        const double f_phi = -std::sin(phi) * f.x + std::cos(phi) * f.y;
        const double f_r = std::cos(phi) * f.x + std::sin(phi) * f.y;
        EXPECT_NEAR(f_phi, 0, 1e-9 * (1 + std::fabs(f_r)));  // no push along the ring
        EXPECT_NEAR(f_r, s.x, 1e-9 * (1 + std::fabs(s.x)));
        EXPECT_NEAR(f.z, s.z, 1e-9 * (1 + std::fabs(s.z)));
        EXPECT_EQ(s.y, 0);  // nor along a straight rod
        pushed += s.x != 0;
    }
    EXPECT_GT(pushed, 300);
}

TEST(RodBase, TheVibratingBaseCarriesItsContactsWithIt) {
    // A sphere at rest relative to the base: at time t its force is that at time 0 (base at
    // rest at level 0) for the same position relative to the base.
    RodBase b = sawtooth(1.0, false, false);
    const force::RodLattice moving = force::rod_lattice(b);
    b.amplitude = 0;
    const force::RodLattice still = force::rod_lattice(b);
    const double w = 6.283185307179586 * 0.4;
    for (double t : {0.1, 0.6, 1.3, 2.2}) {
        const double level = std::sin(w * t), speed = w * std::cos(w * t);
        for (double u : {0.3, 4.0, 9.7, 13.4}) {
            const double z = 0.2 + 3.0 * u / 13.5;  // near the gentle edge
            const Vec3 f = force::rod_base_force<true>(moving, kContact, kRange, 0.2, {u, 0, z + level},
                                                       {0, 0, speed}, 1, t, nullptr);
            const Vec3 g = force::rod_base_force<true>(still, kContact, kRange, 0.2, {u, 0, z}, {0, 0, 0}, 1, 0, nullptr);
            EXPECT_NEAR(f.x, g.x, 1e-9);
            EXPECT_NEAR(f.z, g.z, 1e-9);
        }
    }
}

TEST(RodBase, BadProfilesAreRefusedNamingTheProblem) {
    RodBase b = sawtooth(1.0, false, false);
    b.vertices = {{0, 0}, {5, 3}, {4, 1}, {13.5, 0}};
    EXPECT_THROW(force::rod_lattice(b), InputError);
    b = sawtooth(1.0, false, false);
    b.vertices.back().second = 1;  // does not close
    EXPECT_THROW(force::rod_lattice(b), InputError);
    b = sawtooth(1.0, false, false);
    b.rod_spacing = 0;
    EXPECT_THROW(force::rod_lattice(b), InputError);
}

TEST(RodBase, BackingActsOnlyOnGrainsPressedDeeperThanTheRodsLetThem) {
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> u01(0, 1);
    for (bool rings : {false, true}) {
        RodBase b = sawtooth(1.0, false, rings);
        const force::RodLattice bare = force::rod_lattice(b);
        b.backing = true;
        const force::RodLattice backed = force::rod_lattice(b);
        int same = 0, pushed_out = 0;
        for (int k = 0; k < 4000; ++k) {
            const double u = 1 + 30 * u01(rng), z = -2 + 6 * u01(rng), d = 0.9 + 0.6 * u01(rng);
            const Vec3 x = rings ? Vec3{u, 0, z} : Vec3{u, 1, z};
            const Vec3 v{0, 0, 0};
            // Height of the profile at u (gentle edge from 0 to 3 over each period of 13.5).
            const double w = u - std::floor(u / 13.5) * 13.5, profile = 3 * w / 13.5;
            // The distance to the profile's nearest point, by brute force over its polyline.
            double dist = 1e300;
            for (int m = -1; m <= 3; ++m)
                for (int j = 0; j <= 2000; ++j) {
                    const double s = j / 2000.0;
                    const double pts[2][2] = {{m * 13.5 + s * 13.5, 3 * s}, {(m + 1) * 13.5, 3 * (1 - s)}};
                    for (const auto& q : pts) dist = std::min(dist, std::hypot(u - q[0], z - q[1]));
                }
            const double rc = 0.5 * kRange * d;
            const Vec3 f0 = force::rod_base_force<true>(bare, kContact, kRange, 0.2, x, v, d, 0, nullptr);
            const Vec3 f1 = force::rod_base_force<true>(backed, kContact, kRange, 0.2, x, v, d, 0, nullptr);
            if (z > profile && dist > rc + 1e-3) {
                // Farther from the surface than its reach: the rods alone.
                EXPECT_EQ(f1.x, f0.x);
                EXPECT_EQ(f1.z, f0.z);
                ++same;
            } else if (z < profile - 0.05 && w > 0.5 &&
                       (profile - z) * 13.5 / std::hypot(13.5, 3.0) < 13.5 - w) {
                // Below the gentle edge, nearer to it than to the steep one: pushed back out
                // through it, up and against the slope.
                const Vec3 extra = f1 - f0;
                EXPECT_GT(extra.z, 0) << "at u " << u << " z " << z;
                EXPECT_GT(std::hypot(extra.x, extra.z), kContact.k_n * rc * 0.99);
                ++pushed_out;
            }
        }
        EXPECT_GT(same, 1000);
        EXPECT_GT(pushed_out, 300);
    }
}

TEST(RodBase, CylinderWallPushesInwardOnlyWithinReach) {
    // A sphere of diameter 1 at distance r from the axis of a wall of radius 10: contact when
    // 10 - r < range / 2, force k_n (range/2 - (10 - r)) toward the axis (no damping at rest).
    for (double r : {9.0, 9.6, 9.9, 10.2}) {
        const Vec3 x{r * std::cos(0.7), r * std::sin(0.7), 3};
        const Vec3 v{0, 0, 0};
        const Real d = 1;
        Vec3 f{0, 0, 0};
        const force::CylinderWallForce<false, true> wall{&x, &v, &d, &f, 10, kRange, kContact};
        wall(0);
        const double overlap = 0.5 * kRange - (10 - r);
        if (overlap <= 0) {
            EXPECT_EQ(dot(f, f), 0) << r;
        } else {
            EXPECT_NEAR(std::sqrt(dot(f, f)), kContact.k_n * overlap, 1e-9) << r;
            EXPECT_NEAR(f.x * std::sin(0.7) - f.y * std::cos(0.7), 0, 1e-9);  // radial only
            EXPECT_LT(f.x * x.x + f.y * x.y, 0);                                // inward
            EXPECT_EQ(f.z, 0);
        }
    }
}

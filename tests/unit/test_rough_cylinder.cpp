// SPDX-License-Identifier: MIT
// The drum's rough rotating wall: the embedded spheres turn rigidly with the wall, the
// index arithmetic that finds a particle's wall spheres misses none (against all of them),
// and the contact force turns with the wall (it depends on the particle relative to the wall).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "force/rough_cylinder.hpp"
#include "force/rough_end_cap.hpp"
#include "emergent/error.hpp"
#include "emergent/force_term.hpp"

using namespace emergent;

namespace {

RoughCylinder drum() {
    RoughCylinder w;
    w.radius = 9.5, w.z_lo = 0, w.z_hi = 12, w.omega = 0.2, w.spacing = 2.2, w.sphere_diameter = 1;
    return w;
}

const GranularPair kWall{1000, 5, 10, 0.5};
constexpr double kRange = 1.122462048309373;

Vec3 turn(const Vec3& x, double a) {
    return {std::cos(a) * x.x - std::sin(a) * x.y, std::sin(a) * x.x + std::cos(a) * x.y, x.z};
}

/// Reference for the index search: the contact law summed over every listed wall sphere (each
/// moving at omega z^ x s); counts the touching ones into `touching`.
Vec3 all_spheres_force(const std::vector<Vec3>& spheres, double omega, const Vec3& x,
                       const Vec3& v, double d, double d_wall, int& touching) {
    Vec3 ref{0, 0, 0};
    const double rc = 0.5 * kRange * (d + d_wall);
    for (const Vec3& s : spheres) {
        const Vec3 sep = x - s;
        const double dist = std::sqrt(dot(sep, sep));
        if (dist >= rc) continue;
        ++touching;
        ref += force::contact_force<true, true>((1 / dist) * sep, rc - dist,
                                                v - Vec3{-omega * s.y, omega * s.x, 0}, kWall);
    }
    return ref;
}

}  // namespace

TEST(RoughCylinder, WallSpheresTurnRigidlyWithTheWallOnAStaggeredGrid) {
    const RoughCylinder w = drum();
    const auto at0 = rough_cylinder_spheres(w, 0.0);
    ASSERT_GT(at0.size(), 20u);
    for (double t : {0.7, 13.1, 250.0}) {
        const auto at = rough_cylinder_spheres(w, t);
        ASSERT_EQ(at.size(), at0.size());
        double worst = 0;
        for (std::size_t k = 0; k < at.size(); ++k) {
            const Vec3 d = at[k] - turn(at0[k], w.omega * t);
            worst = std::max(worst, std::sqrt(dot(d, d)));
        }
        EXPECT_LT(worst, 1e-11) << "t=" << t;  // rounding of cos/sin of angles up to ~50 rad
    }
    // Nearest neighbours on the grid are the requested spacing apart, within the stretch
    // needed to close the ring and fit whole rings into the length (a few per cent here).
    double nearest = 1e300;
    for (std::size_t a = 0; a < at0.size(); ++a)
        for (std::size_t b = a + 1; b < at0.size(); ++b) {
            const Vec3 d = at0[a] - at0[b];
            nearest = std::min(nearest, std::sqrt(dot(d, d)));
        }
    EXPECT_NEAR(nearest, w.spacing, 0.05 * w.spacing);
}

TEST(RoughCylinder, FindsEveryTouchingWallSphereAtAnyTime) {
    // Reference: the contact law summed over all wall spheres, plus the smooth surface.
    const RoughCylinder w = drum();
    const force::RoughCylinderLattice l = force::rough_cylinder_lattice(w);
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0, 1);
    int touching = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        const double t = 40 * u(rng), phi = 6.283185307179586 * u(rng);
        const double r = w.radius - 1.3 * u(rng), z = -0.2 + 12.4 * u(rng), d = 0.8 + 0.4 * u(rng);
        const Vec3 x{r * std::cos(phi), r * std::sin(phi), z};
        const Vec3 v{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5};
        force::ContactTally tally;
        const Vec3 f = force::rough_wall_force<true, true>(l, kWall, kRange, w.sphere_diameter,
                                                           x, v, d, t, &tally);
        Vec3 ref = all_spheres_force(rough_cylinder_spheres(w, t), w.omega, x, v, d,
                                     w.sphere_diameter, touching);
        const double gap = w.radius - r, rs = 0.5 * kRange * d;
        if (gap < rs) {
            const Vec3 n{-x.x / r, -x.y / r, 0}, at = (w.radius / r) * Vec3{x.x, x.y, 0};
            ref += force::contact_force<true, true>(n, rs - gap, v - Vec3{-w.omega * at.y, w.omega * at.x, 0}, kWall);
        }
        const Vec3 diff = f - ref;
        ASSERT_LT(std::sqrt(dot(diff, diff)), 1e-9 * (1 + std::sqrt(dot(ref, ref))))
            << "trial " << trial << " t=" << t << " r=" << r << " z=" << z;
    }
    EXPECT_GT(touching, 500);  // the sample really probes wall-sphere contacts
}

TEST(RoughCylinderForce, TurnsWithTheWallAndDoesNotDampSpheresMovingWithIt) {
    const RoughCylinder w = drum();
    const force::RoughCylinderLattice l = force::rough_cylinder_lattice(w);
    // A sphere pressed against the wall near a wall sphere, at rest relative to the wall.
    const Vec3 s = rough_cylinder_spheres(w, 0.0)[40];
    const Vec3 x0 = s - (0.85 / w.radius) * Vec3{s.x, s.y, 0} + Vec3{0, 0, 0.3};
    const Vec3 v0{-w.omega * x0.y, w.omega * x0.x, 0};
    const Vec3 f0 = force::rough_wall_force<true, true>(l, kWall, kRange, 1.0, x0, v0 + Vec3{0.3, -0.2, 0.1}, 1.0, 0, nullptr);
    ASSERT_GT(std::sqrt(dot(f0, f0)), 1.0);
    for (double t : {1.3, 7.9, 31.4}) {
        // Same place and motion relative to the wall, later: the force is the turned force.
        const double a = w.omega * t;
        const Vec3 x = turn(x0, a);
        const Vec3 v = Vec3{-w.omega * x.y, w.omega * x.x, 0} + turn(Vec3{0.3, -0.2, 0.1}, a);
        const Vec3 f = force::rough_wall_force<true, true>(l, kWall, kRange, 1.0, x, v, 1.0, t, nullptr);
        const Vec3 d = f - turn(f0, a);
        EXPECT_LT(std::sqrt(dot(d, d)), 1e-9 * std::sqrt(dot(f0, f0))) << "t=" << t;
    }
    // Co-moving with the wall: the contact separations keep their length, so there is no
    // normal damping. (Sliding friction remains: as for sphere pairs, the model takes the
    // spheres' centre velocities, whose difference omega x (x - x_wall) is tangential.)
    const Vec3 fc = force::rough_wall_force<true, true>(l, kWall, kRange, 1.0, x0, v0, 1.0, 0, nullptr);
    const Vec3 fe = force::rough_wall_force<false, true>(l, kWall, kRange, 1.0, x0, v0, 1.0, 0, nullptr);
    const Vec3 d = fc - fe;
    EXPECT_LT(std::sqrt(dot(d, d)), 1e-9 * std::sqrt(dot(fe, fe)));
}

TEST(RoughEndCap, SpheresTurnRigidlyAndEveryTouchingOneIsFound) {
    RoughEndCap c;
    c.z = 12, c.radius = 8.4, c.omega = -0.2, c.spacing = 2.2, c.sphere_diameter = 1;
    const auto at0 = rough_end_cap_spheres(c, 0.0);
    // A triangular grid of spacing a has 2 / (sqrt(3) a^2) sites per area: ~ 69 in r < 8.4.
    EXPECT_NEAR(double(at0.size()), 3.14159 * 8.4 * 8.4 * 2 / (std::sqrt(3.0) * 2.2 * 2.2), 8);
    const auto later = rough_end_cap_spheres(c, 9.0);
    ASSERT_EQ(later.size(), at0.size());
    for (std::size_t k = 0; k < at0.size(); ++k) {
        const Vec3 d = later[k] - turn(at0[k], c.omega * 9.0);
        ASSERT_LT(std::sqrt(dot(d, d)), 1e-12);
    }
    const force::RoughCapLattice l = force::rough_cap_lattice(c);
    std::mt19937_64 rng(13);
    std::uniform_real_distribution<double> u(0, 1);
    int touching = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        const double t = 40 * u(rng), r = 9 * std::sqrt(u(rng)), phi = 6.283185307179586 * u(rng);
        const Vec3 x{r * std::cos(phi), r * std::sin(phi), c.z - 1.2 * u(rng)};
        const Vec3 v{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5};
        const double d = 0.8 + 0.4 * u(rng);
        const Vec3 f = force::rough_wall_force<true, true>(l, kWall, kRange, c.sphere_diameter, x, v, d, t, nullptr);
        const Vec3 ref = all_spheres_force(rough_end_cap_spheres(c, t), c.omega, x, v, d,
                                           c.sphere_diameter, touching);
        const Vec3 diff = f - ref;
        ASSERT_LT(std::sqrt(dot(diff, diff)), 1e-9 * (1 + std::sqrt(dot(ref, ref)))) << "trial " << trial;
    }
    EXPECT_GT(touching, 500);
}

// Wall spheres closer than a quarter of their diameter are refused in one message naming the
// spacing: at 1e-5 each particle would reach ~1e10 of them (a hang), at 1e-300 the sphere count
// overflows. A quarter is accepted.
TEST(RoughWalls, RefuseSpheresCloserThanAQuarterOfTheirDiameter) {
    RoughCylinder w = drum();
    RoughEndCap c;
    c.z = 12, c.radius = 8.4, c.omega = -0.2, c.sphere_diameter = 1;
    for (const double spacing : {0.2, 1e-5, 1e-300}) {
        w.spacing = c.spacing = spacing;
        for (int wall = 0; wall < 2; ++wall) {
            try {
                if (wall == 0) make_rough_cylinder_wall(w, kWall, kRange);
                else make_rough_end_cap(c, kWall, kRange);
                ADD_FAILURE() << "spacing " << spacing << " accepted";
            } catch (const InputError& e) {
                EXPECT_NE(std::string(e.what()).find("must be at least 0.25 sphere_diameter"), std::string::npos)
                    << e.what();
            }
        }
    }
    w.spacing = c.spacing = 0.25;
    EXPECT_NO_THROW(make_rough_cylinder_wall(w, kWall, kRange));
    EXPECT_NO_THROW(make_rough_end_cap(c, kWall, kRange));
}

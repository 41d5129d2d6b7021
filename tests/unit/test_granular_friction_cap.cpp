// SPDX-License-Identifier: MIT
// The contact law's sliding friction with normal damping on (paper eq. 8): the tangential
// force is -gamma_s v_t below the Coulomb cap and mu |f_l + f_d| along -v_t at it, where the
// normal force f_l + f_d = (k_n overlap - gamma_n v_n) n includes the damping (and pulls when a
// contact separates fast enough; the cap then takes its size, as eq. 8 writes |f_l + f_d|).
// Checked for the law itself and for the pair and plane-wall loops that apply it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "emergent/backend_particles.hpp"
#include "emergent/force_term.hpp"
#include "force/granular_contact.hpp"

using namespace emergent;

namespace {

const GranularPair kContact{1000, 30, 50, 0.5};  // gamma_n large enough to matter at v_n ~ 1

/// The law as the paper writes it (independent of the code's arrangement): normal force
/// k_n overlap - gamma_n (n.v) along n, and -min(gamma_s |v_t|, mu |normal|) v_t / |v_t|.
Vec3 reference_force(const Vec3& n, double overlap, const Vec3& v, const GranularPair& p) {
    const double normal = p.k_n * overlap - p.gamma_n * dot(n, v);
    const Vec3 v_t = v - dot(n, v) * n;
    const double speed = std::sqrt(dot(v_t, v_t));
    const double sliding = std::min(p.gamma_s * speed, p.mu * std::abs(normal));
    return normal * n - (speed > 0 ? sliding / speed : 0.0) * v_t;
}

/// What each random contact exercises.
struct Tally {
    int viscous = 0, capped = 0;
    int cap_raised_by_damping = 0;   ///< capped at mu |f_l + f_d| > mu k_n overlap
    int cap_lowered_by_damping = 0;  ///< viscous mu k_n overlap would cap, but damping lowered it
    int tensile = 0;  ///< separating fast enough that f_l + f_d pulls (the cap takes its size)
};

/// Checks one contact force f against the reference and the cap; counts its regime.
void check_contact(const Vec3& f, const Vec3& n, double overlap, const Vec3& v,
                   const GranularPair& p, Tally& tally) {
    const Vec3 ref = reference_force(n, overlap, v, p);
    const double normal = p.k_n * overlap - p.gamma_n * dot(n, v);
    const Vec3 v_t = v - dot(n, v) * n, f_t = f - dot(f, n) * n;
    const double speed = std::sqrt(dot(v_t, v_t)), ft = std::sqrt(dot(f_t, f_t));
    // Forces here are <~ 1e3 from terms of that size: a few roundings, 1e-12 relative.
    const double tol = 1e-12 * (std::abs(normal) + p.gamma_s * speed + 1);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(f[k], ref[k], tol);
    EXPECT_NEAR(dot(f, n), normal, tol);           // damping in the normal force
    EXPECT_LE(ft, p.mu * std::abs(normal) + tol);  // the Coulomb cap holds
    if (p.gamma_s * speed < p.mu * std::abs(normal)) {
        ++tally.viscous;
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(f_t[k], -p.gamma_s * v_t[k], tol);
    } else {
        ++tally.capped;
        EXPECT_NEAR(ft, p.mu * std::abs(normal), tol);
        EXPECT_NEAR(dot(f_t, v_t), -ft * speed, tol * speed);  // against the sliding
        tally.cap_raised_by_damping += p.mu * std::abs(normal) > 1.05 * p.mu * p.k_n * overlap;
    }
    tally.tensile += normal < 0;
    tally.cap_lowered_by_damping +=
        p.gamma_s * speed < p.mu * p.k_n * overlap && p.gamma_s * speed >= p.mu * std::abs(normal);
}

struct RandomContact {
    Vec3 n, v;
    double overlap;
};

RandomContact random_contact(std::mt19937_64& rng) {
    std::normal_distribution<double> normal(0, 1);
    std::uniform_real_distribution<double> u01(0, 1);
    Vec3 n{normal(rng), normal(rng), normal(rng)};
    n = (1 / std::sqrt(dot(n, n))) * n;
    // Overlaps up to 0.05 (k_n overlap <= 50) and relative speeds ~ 0.5 (gamma_n v_n ~ 15):
    // damping changes the normal force, and so the cap, by tens of per cent either way, and
    // both regimes occur (about a fifth of the contacts slide below the cap).
    return {n, {0.5 * normal(rng), 0.5 * normal(rng), 0.5 * normal(rng)}, 0.05 * u01(rng)};
}

/// Every regime was met (of n contacts: ~18 % viscous, ~38 % capped above mu k_n overlap by
/// damping, ~3 % capped below it), so no branch of the check went untried.
void expect_all_regimes(const Tally& t, int n) {
    EXPECT_GT(t.viscous, n / 10);
    EXPECT_GT(t.capped, n / 2);
    EXPECT_GT(t.cap_raised_by_damping, n / 5);
    EXPECT_GT(t.cap_lowered_by_damping, n / 100);
    EXPECT_GT(t.tensile, n / 20);
}

}  // namespace

TEST(FrictionCap, TheLawCapsSlidingAtMuTimesTheDampedNormalForce) {
    std::mt19937_64 rng(43);
    Tally tally;
    for (int k = 0; k < 4000; ++k) {
        const RandomContact c = random_contact(rng);
        check_contact(force::contact_force<true, true>(c.n, c.overlap, c.v, kContact), c.n,
                      c.overlap, c.v, kContact, tally);
    }
    expect_all_regimes(tally, 4000);
}

TEST(FrictionCap, PairAndPlaneWallLoopsApplyTheCappedLaw) {
    // Two spheres (diameters 1 and 1.2, r_c = 1.1) through the pair term's full-list loop, and
    // a sphere on a plane floor moving at (0.3, -0.2, 0), both with damping and friction on.
    GranularSettings g;
    g.pairs = {kContact};
    g.max_diameter = 1.2;
    const auto pairs = make_granular_contacts(g);
    const Vec3 floor_velocity{0.3, -0.2, 0};
    const auto floor = make_plane_wall(2, 0.0, +1, kContact, 1.0, floor_velocity);
    const std::vector<double> mass{1.0};
    std::mt19937_64 rng(47);
    Tally pair_tally, wall_tally;
    for (int k = 0; k < 1000; ++k) {
        const RandomContact c = random_contact(rng);
        ParticleStore s;
        s.enable_diameters();
        const Vec3 x1{5, 5, 5}, v1{0.1, 0.2, -0.3};
        s.add_owned(x1 + (1.1 - c.overlap) * c.n, v1 + c.v, 0, 0, 1.0);
        s.add_owned(x1, v1, 0, 1, 1.2);
        s.force[0] = s.force[1] = {0, 0, 0};
        BackendParticles p = host_view(s, mass);
        const std::uint32_t offset[3] = {0, 1, 2}, index[2] = {1, 0};
        p.list_offset = offset, p.list_index = index;
        ForceContext context;
        context.mass = &mass;
        ForceSums sums;
        pairs->add_forces_on_backend(p, context, false, sums);
        // The loop recomputes n, the overlap and v_rel from the store: compare with those.
        const Vec3 r = s.position[0] - s.position[1];
        const double dist = std::sqrt(dot(r, r));
        check_contact(s.force[0], (1 / dist) * r, 1.1 - dist, s.velocity[0] - s.velocity[1],
                      kContact, pair_tally);
        EXPECT_EQ(s.force[1].x, -s.force[0].x);

        // The same relative motion against the moving floor (the sphere above it, n = +z).
        ParticleStore w;
        w.enable_diameters();
        const double overlap = c.overlap;
        w.add_owned({1, 2, 0.5 - overlap}, floor_velocity + c.v, 0, 0, 1.0);
        w.force[0] = {0, 0, 0};
        BackendParticles q = host_view(w, mass);
        floor->add_forces_on_backend(q, context, false, sums);
        const double gap = w.position[0].z;  // the loop's overlap: 0.5 - z
        check_contact(w.force[0], {0, 0, 1}, 0.5 - gap, w.velocity[0] - floor_velocity, kContact,
                      wall_tally);
    }
    expect_all_regimes(pair_tally, 1000);
    expect_all_regimes(wall_tally, 1000);
}

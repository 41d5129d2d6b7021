// SPDX-License-Identifier: MIT
// Pair laws that have an energy: the force is minus the energy's gradient (central finite
// differences), on each side of every branch point, and both vanish beyond the cut-off. The
// capsid model's sphere-and-site law and the granular contact's elastic part, as the engine
// evaluates them (the law itself, and the force terms' full-list loops on two particles), and
// the uniform field. (Lennard-Jones: test_lennard_jones.cpp; walls: test_wall_force_energy.cpp.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "emergent/backend_particles.hpp"
#include "emergent/force_term.hpp"
#include "force/site_attraction.hpp"
#include "support/finite_difference.hpp"

using namespace emergent;

namespace {

/// The capsid scene's attraction (its defaults): sites of species 1 and 2 are partners.
SiteAttraction capsid_sites() {
    SiteAttraction s;
    s.first_site = 1;
    s.partner = {1, 0};
    s.epsilon = 0.09, s.range = 3, s.harmonic_range = 0.3;
    return s;
}

/// A unit vector off every axis, so that each Cartesian component of the force is tested.
const Vec3 kDirection{1.0 / 3, 2.0 / 3, -2.0 / 3};

double law_energy(const force::SphereSiteLaw& law, int a, int b, const Vec3& d) {
    Real u = 0;
    law.between(a, b, d, &u);
    return u;
}

Vec3 law_force(const force::SphereSiteLaw& law, int a, int b, const Vec3& d) {
    return law.between(a, b, d, nullptr) * d;
}

/// Force on particle 0 and the total energy of two particles (species s0, s1; diameters d0,
/// d1) under `term`'s back-end form over a full list, run on the host.
struct PairProbe {
    Vec3 f0, f1;
    double energy;
};
PairProbe two_particles(const ForceTerm& term, const Vec3& x0, const Vec3& x1, int s0, int s1,
                        double d0 = 1, double d1 = 1) {
    ParticleStore s;
    s.enable_diameters();
    s.add_owned(x0, {0, 0, 0}, s0, 0, d0);
    s.add_owned(x1, {0, 0, 0}, s1, 1, d1);
    s.force[0] = s.force[1] = {0, 0, 0};
    const std::vector<double> mass(3, 1.0);
    BackendParticles p = host_view(s, mass);
    const std::uint32_t offset[3] = {0, 1, 2}, index[2] = {1, 0};
    p.list_offset = offset, p.list_index = index;
    Real energy[2], virial[2], overlap[2];
    p.energy = energy, p.virial = virial, p.overlap = overlap;
    ForceContext c;
    c.mass = &mass;
    ForceSums sums;
    term.add_forces_on_backend(p, c, true, sums);
    return {s.force[0], s.force[1], sums.potential};
}

}  // namespace

TEST(SiteAttractionEnergy, ForceIsMinusEnergyGradientOnBothSidesOfTheBranchPoint) {
    const force::SphereSiteLaw law = force::sphere_site_law(capsid_sites());
    ASSERT_EQ(law.kind(1, 2), force::SphereSiteLaw::kAttraction);
    // Harmonic well below r_h = 0.3, e (1/r_a^2 - 1/r^2) from there to r_a = 3.
    for (double r : {0.02, 0.1, 0.2, 0.29, 0.31, 0.45, 0.8, 1.5, 2.5, 2.99}) {
        const Vec3 d = r * kDirection;
        // Step h = 1e-5 r. Truncation h^2 |U'''| / 6: 0 in the harmonic well (U quadratic),
        // (h^2 / 6) 24 e / r^5 = 2e-10 |F| beyond it (|F| = 2 e / r^3); round-off
        // eps |U| / h <= eps (r |F| / 2) / h ~ 1e-11 |F|. So 1e-7 |F| is far above the
        // difference's own error and far below any wrong factor or sign.
        const double h = 1e-5 * r;
        const Vec3 f = law_force(law, 1, 2, d);
        const Vec3 fd =
            fixtures::minus_gradient([&](const Vec3& y) { return law_energy(law, 1, 2, y); }, d, h);
        const double tol = 1e-7 * std::sqrt(dot(f, f));
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(f[k], fd[k], tol) << "r = " << r << ", axis " << k;
        EXPECT_LT(dot(f, d), 0) << "attraction pulls the partner sites together at r = " << r;
    }
}

TEST(SiteAttractionEnergy, ContinuousAtTheBranchPointZeroAtTheRangeAndNothingBeyond) {
    const SiteAttraction s = capsid_sites();
    const force::SphereSiteLaw law = force::sphere_site_law(s);
    const double e = s.epsilon, ra = s.range, rh = s.harmonic_range;
    // Closed forms (force_term.hpp): U(r_h) = e (1/r_a^2 - 1/r_h^2), |F(r_h)| = 2 e / r_h^3 from
    // both branches; the well's bottom U(0) = e (1/r_a^2 - 2/r_h^2). Relative 1e-12: a few
    // roundings of numbers of order 1, where a branch off by anything real differs at 1e-3.
    const double u_rh = e * (1 / (ra * ra) - 1 / (rh * rh)), f_rh = 2 * e / (rh * rh * rh);
    for (double r : {rh * (1 - 1e-13), rh * (1 + 1e-13)}) {
        const Vec3 d = r * kDirection;
        EXPECT_NEAR(law_energy(law, 1, 2, d), u_rh, 1e-12 * std::abs(u_rh)) << r;
        EXPECT_NEAR(std::sqrt(dot(law_force(law, 1, 2, d), law_force(law, 1, 2, d))), f_rh,
                    1e-12 * f_rh)
            << r;
    }
    const double u0 = e * (1 / (ra * ra) - 2 / (rh * rh));
    EXPECT_NEAR(law_energy(law, 1, 2, 1e-9 * kDirection), u0, 1e-12 * std::abs(u0));
    // At the range the energy reaches 0 (1e-9 r_a below it, U = -2 e 1e-9 / r_a^2 = -2e-11)
    // and the force keeps its published step of 2 e / r_a^3; beyond, nothing at all.
    const Vec3 below = ra * (1 - 1e-9) * kDirection;
    EXPECT_NEAR(law_energy(law, 1, 2, below), 0.0, 1e-10);
    EXPECT_NEAR(std::sqrt(dot(law_force(law, 1, 2, below), law_force(law, 1, 2, below))),
                2 * e / (ra * ra * ra), 1e-8 * e);
    for (double r : {ra * (1 + 1e-12), 3.5, 10.0}) {
        Real u = 0;
        EXPECT_EQ(law.between(1, 2, r * kDirection, &u), 0.0) << r;
        EXPECT_EQ(u, 0.0) << r;
    }
    // Sites that are not partners, and volume with sites, never interact.
    EXPECT_EQ(law.between(1, 1, 0.5 * kDirection, nullptr), 0.0);
    EXPECT_EQ(law.between(0, 2, 0.5 * kDirection, nullptr), 0.0);
}

TEST(SiteAttractionEnergy, SphereRepulsionIsMinusEnergyGradientAndVanishesAtItsMinimum) {
    const force::SphereSiteLaw law = force::sphere_site_law(capsid_sites());
    ASSERT_EQ(law.kind(0, 0), force::SphereSiteLaw::kRepulsion);
    for (double r : {0.85, 0.95, 1.0, 1.05, 1.1}) {
        // As for Lennard-Jones (test_lennard_jones.cpp): h = 1e-5, truncation
        // h^2 |U'''| / 6 <= 1e-10 * 5e4 / 6 ~ 1e-6 at r = 0.85 where |F| ~ 500, round-off ~ 1e-11.
        const Vec3 d = r * kDirection;
        const Vec3 f = law_force(law, 0, 0, d);
        const Vec3 fd = fixtures::minus_gradient(
            [&](const Vec3& y) { return law_energy(law, 0, 0, y); }, d, 1e-5);
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(f[k], fd[k], 1e-6 * std::max(1.0, std::sqrt(dot(f, f)))) << "r = " << r;
    }
    // Cut and shifted at the minimum 2^(1/6): energy and force both reach 0 there (1e-9 below
    // it, |F| = U''(r_m) 1.1e-9 = 6e-8 and U ~ 1e-17).
    const Vec3 at_min = 1.122462048309373 * (1 - 1e-9) * kDirection;
    EXPECT_NEAR(law_energy(law, 0, 0, at_min), 0.0, 1e-12);
    EXPECT_NEAR(law.between(0, 0, at_min, nullptr), 0.0, 1e-6);
}

TEST(SiteAttractionEnergy, TheTermsFullListLoopSumsTheSameEnergyItsForcesDeriveFrom) {
    // The force term as the engine builds it, on two partner sites: the force on each member
    // is minus the gradient of the pair's energy that the loop reports (each member's half).
    const auto term = make_soft_spheres_and_sites(capsid_sites());
    const Vec3 x1{4, 5, 6};
    for (double r : {0.2, 1.2}) {  // one point in each branch
        const Vec3 x0 = x1 + r * kDirection;
        const PairProbe at = two_particles(*term, x0, x1, 1, 2);
        const Vec3 fd = fixtures::minus_gradient(
            [&](const Vec3& y) { return two_particles(*term, y, x1, 1, 2).energy; }, x0, 1e-5 * r);
        // As in the law's test (the energy is the law's, summed in two halves): 1e-7 |F|.
        const double tol = 1e-7 * std::sqrt(dot(at.f0, at.f0));
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(at.f0[k], fd[k], tol) << "r = " << r;
            EXPECT_EQ(at.f1[k], -at.f0[k]);  // Newton's third law, bit for bit
        }
        EXPECT_NEAR(at.energy, law_energy(force::sphere_site_law(capsid_sites()), 1, 2, x0 - x1),
                    1e-15);
    }
}

TEST(GranularContactEnergy, ElasticForceIsMinusGradientOfTheOverlapEnergy) {
    // Damping and friction off: the contact is conservative with u = (k_n / 2)(r_c - r)^2,
    // r_c = range (d_0 + d_1) / 2, the energy the loop reports on sampling steps.
    GranularSettings g;
    g.pairs = {GranularPair{1000, 0, 0, 0}};
    g.range_factor = 1.122462048309373;  // the paper's convention
    g.max_diameter = 1.2;
    const auto term = make_granular_contacts(g);
    ASSERT_TRUE(term->conservative());
    const double rc = 0.5 * g.range_factor * (1.0 + 1.2);
    const Vec3 x1{5, 5, 5};
    for (double overlap : {0.2, 0.05, 0.01, 1e-4}) {
        const Vec3 x0 = x1 + (rc - overlap) * kDirection;
        const PairProbe at = two_particles(*term, x0, x1, 0, 0, 1.0, 1.2);
        // u is quadratic in r, r(x) smooth at r ~ 1: |U'''| <~ k_n (3 / r) ~ 3e3, so with
        // h = 1e-6 the truncation is ~ 5e-10 and the round-off eps |U| / h <= 5e-9 (U <= 20):
        // 1e-6 max(1, |F|) sits well above both and far below a wrong factor (F ~ 10 .. 200).
        const Vec3 fd = fixtures::minus_gradient(
            [&](const Vec3& y) { return two_particles(*term, y, x1, 0, 0, 1.0, 1.2).energy; }, x0,
            1e-6);
        const double magnitude = std::sqrt(dot(at.f0, at.f0));
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(at.f0[k], fd[k], 1e-6 * std::max(1.0, magnitude)) << overlap;
        EXPECT_NEAR(at.energy, 0.5 * 1000 * overlap * overlap, 1e-9 * (1 + at.energy)) << overlap;
        EXPECT_NEAR(magnitude, 1000 * overlap, 1e-9 * 1000) << overlap;  // the spring, k_n overlap
        EXPECT_GT(dot(at.f0, x0 - x1), 0) << "overlap repels";
    }
    // Beyond r_c: no force, no energy.
    const PairProbe apart = two_particles(*term, x1 + (rc + 1e-9) * kDirection, x1, 0, 0, 1.0, 1.2);
    EXPECT_EQ(dot(apart.f0, apart.f0), 0.0);
    EXPECT_EQ(apart.energy, 0.0);
}

TEST(UniformFieldEnergy, ForceIsMinusGradientOfTheFieldEnergyForEachMass) {
    // Gravity as the engine applies it (the term's back-end form): f = m g, u = -m g.x, with
    // the mass of the particle's species. u is linear, so the central difference is exact but
    // for round-off: eps |u| / h ~ 1e-16 * 20 / 1e-3 ~ 1e-12.
    const Vec3 g{0.3, -0.2, -5};
    const auto field = make_uniform_field(g);
    const std::vector<double> mass{1.0, 2.5};
    auto evaluate = [&](const Vec3& x, int species, Vec3* force) {
        ParticleStore s;
        s.add_owned(x, {0, 0, 0}, species, 0);
        s.force[0] = {0, 0, 0};
        BackendParticles p = host_view(s, mass);
        ForceContext c;
        c.mass = &mass;
        ForceSums sums;
        field->add_forces_on_backend(p, c, true, sums);
        if (force) *force = s.force[0];
        return sums.potential;
    };
    for (int species : {0, 1}) {
        const Vec3 x{1.5, -2.0, 3.25};
        Vec3 f;
        evaluate(x, species, &f);
        const Vec3 fd = fixtures::minus_gradient(
            [&](const Vec3& y) { return evaluate(y, species, nullptr); }, x, 1e-3);
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(f[k], fd[k], 1e-9) << "species " << species;
            EXPECT_NEAR(f[k], mass[std::size_t(species)] * g[k], 1e-15);
        }
    }
}

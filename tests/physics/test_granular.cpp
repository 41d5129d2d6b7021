// SPDX-License-Identifier: MIT
// Granular contact law against the analytic damped linear spring and Coulomb sliding.
#include <gtest/gtest.h>

#include <cmath>

#include "emergent/random.hpp"
#include "emergent/simulation.hpp"

using namespace emergent;

namespace {

Box open_box(double L, bool periodic_z) {
    Box b;
    b.hi = {L, L, L};
    b.periodic[2] = periodic_z;
    return b;
}

struct Collision {
    double restitution, contact_time;
};

/// Two unit spheres (m = 1) meet head on at relative speed 1; returns e and the contact time.
Collision head_on(double k_n, double gamma_n, double dt) {
    RunSettings rs;
    rs.dt = dt;
    rs.skin = 0.2;
    Simulation sim(MPI_COMM_SELF, rs);
    sim.set_box(open_box(10, true));
    sim.set_species_masses({1.0});
    GranularSettings g;
    g.pairs = {GranularPair{k_n, gamma_n, 0, 0}};
    sim.add_force(make_granular_contacts(g));
    sim.add_particle({4.45, 5, 5}, {0.5, 0, 0}, 0, 0);
    sim.add_particle({5.55, 5, 5}, {-0.5, 0, 0}, 0, 1);
    sim.initialise();
    long contact_steps = 0;
    for (int k = 0; k < 1000000; ++k) {
        sim.step(false);
        const ParticleStore& s = sim.particles();
        const double dist = std::abs(s.position[1].x - s.position[0].x);
        if (dist < 1.0) ++contact_steps;
        if (contact_steps > 0 && dist > 1.05) break;
    }
    const ParticleStore& s = sim.particles();
    const double v_rel = s.velocity[s.id[0] == 0 ? 1 : 0].x - s.velocity[s.id[0] == 0 ? 0 : 1].x;
    return {v_rel / 1.0, contact_steps * dt};
}

}  // namespace

TEST(GranularContact, HeadOnCollisionMatchesTheDampedLinearSpring) {
    // Relative coordinate: mu x'' = -k x - gamma x', mu = m/2 = 0.5 (paper's k_n = 1000,
    // gamma_n = 5). Contact lasts while the overlap is positive: t_c = pi / omega_d,
    // omega_d = sqrt(k/mu - (gamma / 2 mu)^2), and e = exp(-(gamma / 2 mu) t_c).
    const double k = 1000, gamma = 5, mu = 0.5;
    const double beta = gamma / (2 * mu), omega_d = std::sqrt(k / mu - beta * beta);
    const double t_c = M_PI / omega_d, e = std::exp(-beta * t_c);
    const double dt = t_c / 400;
    const Collision c = head_on(k, gamma, dt);
    std::printf("e = %.5f (analytic %.5f), t_c = %.5f (analytic %.5f)\n", c.restitution, e,
                c.contact_time, t_c);
    // Velocity Verlet with a velocity-dependent force is first order in the damping:
    // error ~ beta dt ~ 1e-3 relative; the contact time is counted in whole steps (+-dt).
    EXPECT_NEAR(c.restitution, e, 3e-3) << "analytic e = " << e;
    EXPECT_NEAR(c.contact_time, t_c, 2 * dt + 1e-3 * t_c) << "analytic t_c = " << t_c;
    // Without damping the collision is elastic and lasts pi / omega_0.
    const Collision elastic = head_on(k, 0, dt);
    EXPECT_NEAR(elastic.restitution, 1.0, 1e-4);
    EXPECT_NEAR(elastic.contact_time, M_PI / std::sqrt(k / mu), 2 * dt);
}

TEST(GranularContact, SphereSlidingOnAPlaneFollowsCoulombThenViscousFriction) {
    // Sphere on a floor under gravity g = 5 (sphere-wall: k_n = 1000, gamma_n = 5,
    // gamma_s = 10, mu = 0.5). While gamma_s v > mu m g (v > 0.25) friction is the Coulomb cap:
    // constant deceleration mu g = 2.5; below, viscous: v = 0.25 exp(-gamma_s (t - t1) / m).
    const double g = 5, mu = 0.5, gamma_s = 10, v0 = 3;
    RunSettings rs;
    rs.dt = 1e-4;
    rs.skin = 0.2;
    Simulation sim(MPI_COMM_SELF, rs);
    sim.set_box(open_box(40, false));
    sim.set_species_masses({1.0});
    sim.add_force(make_uniform_field({0, 0, -g}));
    sim.add_force(make_plane_wall(2, 0.0, +1, GranularPair{1000, 5, gamma_s, mu}));
    sim.add_particle({5, 5, 0.5 - g / 1000}, {v0, 0, 0}, 0, 0);  // resting overlap m g / k_n
    sim.initialise();
    const double v_switch = mu * g / gamma_s, t1 = (v0 - v_switch) / (mu * g);
    auto expected = [&](double t) {
        return t < t1 ? v0 - mu * g * t : v_switch * std::exp(-gamma_s * (t - t1));
    };
    for (double t_check : {0.4, 0.8, 1.0, t1 + 0.1, t1 + 0.25}) {
        while (sim.time() < t_check - 1e-9) sim.step(false);
        const double v = sim.particles().velocity[0].x;
        std::printf("t = %.3f: v = %.5f (expected %.5f)\n", sim.time(), v, expected(sim.time()));
        // Vertical jitter of the contact (damped in ~0.4 tau) modulates the Coulomb force by
        // well under 1 %; the time grid adds mu g dt = 2.5e-4.
        EXPECT_NEAR(v, expected(sim.time()), 0.01 * std::abs(expected(sim.time())) + 1e-3)
            << "t = " << sim.time();
    }
    EXPECT_NEAR(sim.particles().position[0].z, 0.5 - g / 1000, 1e-4);
}

TEST(GranularContact, SettledBedRestsOnTheFloor) {
    // 216 spheres (d = 1, m = 1, mildly polydisperse) fall onto a floor under g = 5 and settle
    // through damping and friction. At rest the floor must carry the whole weight: the sum of
    // k_n * overlap over floor contacts, computed here from positions alone, equals N m g.
    const double g = 5, k_floor = 2000;
    RunSettings rs;
    rs.dt = 0.002;
    rs.skin = 0.3;
    Simulation sim(MPI_COMM_WORLD, rs);
    Box box;
    box.hi = {7.2, 7.2, 40};
    box.periodic[2] = false;
    sim.set_box(box);
    sim.set_species_masses({1.0});
    GranularSettings gs;
    gs.pairs = {GranularPair{2000, 10, 5, 0.5}};
    gs.max_diameter = 1.05;
    sim.add_force(make_granular_contacts(gs));
    sim.add_force(make_uniform_field({0, 0, -g}));
    sim.add_force(make_plane_wall(2, 0.0, +1, GranularPair{k_floor, 10, 5, 0.5}));
    std::int64_t id = 0;
    for (int z = 0; z < 6; ++z)
        for (int y = 0; y < 6; ++y)
            for (int x = 0; x < 6; ++x, ++id)
                sim.add_particle({0.6 + 1.2 * x, 0.6 + 1.2 * y, 1.0 + 1.2 * z}, {0, 0, 0}, 0, id,
                                 0.95 + 0.1 * uniform_open(7, id, 0));
    sim.initialise();
    for (int k = 0; k < 15000; ++k) sim.step(false);  // 30 tau: many damping times
    const ParticleStore& s = sim.particles();
    double floor_force = 0, kinetic = 0;
    for (std::size_t i = 0; i < s.n_owned(); ++i) {
        const double overlap = 0.5 * s.diameter[i] - s.position[i].z;
        if (overlap > 0) floor_force += k_floor * overlap;
        kinetic += 0.5 * dot(s.velocity[i], s.velocity[i]);
    }
    MPI_Allreduce(MPI_IN_PLACE, &floor_force, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    MPI_Allreduce(MPI_IN_PLACE, &kinetic, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    EXPECT_LT(kinetic / 216, 1e-4);  // at rest: residual motion far below g d
    // Damping forces vanish at rest; 1 % covers the residual motion.
    EXPECT_NEAR(floor_force, 216 * 1.0 * g, 0.01 * 216 * g);
    std::printf("floor carries %.2f, weight %.2f, kinetic per particle %.2e\n", floor_force,
                216 * g, kinetic / 216);
}

TEST(GranularContact, LargestOverlapIsReportedForPairsAndWalls) {
    // Undamped contacts: the overlap peaks at amplitude v / omega = v sqrt(m_eff / k).
    // Reported in sphere diameters (1 here). Pair: two unit spheres at relative speed 1,
    // m_eff = 1/2. Wall: one unit sphere at speed 1 onto a wall, m_eff = 1. Sampled every step
    // with dt = t_c / 400, the
    // sampled peak is within (omega dt)^2 / 8 ~ 1e-5 relative of the true one.
    const double k = 1000;
    auto largest = [&](bool wall) {
        RunSettings rs;
        rs.dt = M_PI / std::sqrt(k / 0.5) / 400;
        rs.skin = 0.2;
        Simulation sim(MPI_COMM_SELF, rs);
        sim.set_box(open_box(10, true));
        sim.set_species_masses({1.0});
        GranularSettings g;
        g.pairs = {GranularPair{k, 0, 0, 0}};
        sim.add_force(make_granular_contacts(g));
        if (wall) {
            sim.add_force(make_plane_wall(0, 1.0, +1, GranularPair{k, 0, 0, 0}));
            sim.add_particle({1.6, 5, 5}, {-1, 0, 0}, 0, 0);
        } else {
            sim.add_particle({4.45, 5, 5}, {0.5, 0, 0}, 0, 0);
            sim.add_particle({5.55, 5, 5}, {-0.5, 0, 0}, 0, 1);
        }
        sim.initialise();
        double peak = -1;
        for (int s = 0; s < 1200; ++s) {
            sim.step(true);
            peak = std::max(peak, sim.measure().max_overlap);
        }
        return peak;
    };
    EXPECT_NEAR(largest(false), std::sqrt(0.5 / k) / 1.0, 1e-4 * std::sqrt(0.5 / k));
    EXPECT_NEAR(largest(true), std::sqrt(1.0 / k), 1e-4 * std::sqrt(1.0 / k));
}

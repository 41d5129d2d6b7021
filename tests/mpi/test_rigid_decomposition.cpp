// SPDX-License-Identifier: MIT
// Rigid bodies across ranks: a colliding cluster of tetrahedra straddling the domain
// boundaries keeps total momentum and angular momentum to round-off and retraces the one-rank
// run. (HOOMD-blue once shipped rigid bodies that broke momentum conservation on more than one
// rank; this is the test for that.)
#include <gtest/gtest.h>

#include <cmath>

#include "emergent/kit/body_shapes.hpp"
#include "emergent/random.hpp"
#include "emergent/simulation.hpp"
#include "support/scene_fixture.hpp"

using namespace emergent;

namespace {

std::unique_ptr<Simulation> cluster(MPI_Comm comm) {
    RunSettings rs;
    rs.dt = 0.002;
    rs.skin = 0.3;
    auto sim = std::make_unique<Simulation>(comm, rs);
    Box box;
    box.hi = {24, 24, 24};
    sim->set_box(box);
    sim->set_species_masses({1.0, 2.0});
    GranularSettings g;
    g.n_species = 2;
    // Elastic and damped normal contacts only: central pair forces, so angular momentum is
    // an exact invariant of the discrete dynamics (velocity Verlet, NO_SQUISH kicks and free
    // rotations each preserve it).
    g.pairs = {GranularPair{1000, 5, 0, 0}, GranularPair{1000, 5, 0, 0}, GranularPair{1000, 5, 0, 0},
               GranularPair{1000, 5, 0, 0}};
    g.max_diameter = 1.0;
    sim->add_force(make_granular_contacts(g));
    // Small (arm 0.6) and big (arm 1.2) tetrahedra as in the drum; the big one is asymmetric
    // in mass (two heavy spheres) so it is no spherical top.
    const int small = sim->add_body_kind(regular_tetrahedron(0.6), {0, 0, 0, 0}, {1, 1, 1, 1});
    const int big = sim->add_body_kind(regular_tetrahedron(1.2), {0, 1, 0, 1}, {1, 1, 1, 1});
    std::int64_t id = 0;
    for (int z = 0; z < 3; ++z)
        for (int y = 0; y < 3; ++y)
            for (int x = 0; x < 3; ++x, ++id) {
                // Centred on (12, 12, 12), where the domains of 2 and 4 ranks meet.
                const Vec3 c{12 + 2.6 * (x - 1), 12 + 2.6 * (y - 1), 12 + 2.6 * (z - 1)};
                const Quat q = normalized(Quat{gaussian(4, id, 0), gaussian(4, id, 1),
                                               gaussian(4, id, 2), gaussian(4, id, 3)});
                // Thermal motion plus a common drift of (4, 3, 2): within the run every body
                // crosses the domain boundaries at 12 (and the cluster stays clear of the
                // periodic boundary, so no interaction crosses it and L stays an invariant).
                const Vec3 v = Vec3{4, 3, 2} + 2 * Vec3{gaussian(4, id, 4), gaussian(4, id, 5),
                                                        gaussian(4, id, 6)};
                const Vec3 w{gaussian(4, id, 7), gaussian(4, id, 8), gaussian(4, id, 9)};
                sim->add_body(id % 3 == 0 ? big : small, c, q, v, w, id, 4 * id);
            }
    sim->initialise();
    return sim;
}

struct Trace {
    std::vector<double> kinetic;
    ThermoSample first, last;
};

Trace run(MPI_Comm comm) {
    auto sim = cluster(comm);
    Trace t;
    t.first = sim->measure();
    for (int k = 1; k <= 500; ++k) {
        sim->step(k % 50 == 0);
        if (k % 50 == 0) t.kinetic.push_back(sim->measure().kinetic);
    }
    t.last = sim->measure();
    return t;
}

double norm(const Vec3& v) { return std::sqrt(dot(v, v)); }

}  // namespace

TEST(RigidDecomposition, MomentumAndAngularMomentumConserved) {
    const Trace d = run(MPI_COMM_WORLD);
    // Scales: |p| of the cluster ~ 27 * 8 * 5 ~ 1e3, |L| about the origin ~ 1e3 * 12 ~ 1e4.
    EXPECT_LT(norm(d.last.momentum - d.first.momentum), 1e-9);
    EXPECT_LT(norm(d.last.angular_momentum - d.first.angular_momentum), 1e-8);
    // Collisions happened (damping removed energy), or nothing was tested: the thermal part
    // of the kinetic energy is ~9 (the drift's ~13 is untouched by internal forces); without
    // collisions the loss would be exactly zero.
    EXPECT_GT(d.first.kinetic - d.kinetic.back(), 0.05);
    std::printf("kinetic energy %.6f -> %.6f; |dP| = %.1e, |dL| = %.1e\n", d.first.kinetic,
                d.kinetic.back(), norm(d.last.momentum - d.first.momentum),
                norm(d.last.angular_momentum - d.first.angular_momentum));
}

// Run with several ranks only (ctest's 1-rank variant leaves out *RankCount* tests).
TEST(RigidDecomposition, SameDynamicsOnAnyRankCount) {
    const Trace d = run(MPI_COMM_WORLD);
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank != 0) return;
    const Trace s = run(MPI_COMM_SELF);
    for (std::size_t k = 0; k < s.kinetic.size(); ++k)
        EXPECT_TRUE(emergent::testing::relative_close(d.kinetic[k], s.kinetic[k], 1e-9))
            << "sample " << k << ": " << d.kinetic[k] << " vs " << s.kinetic[k];
}

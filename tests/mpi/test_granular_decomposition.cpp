// SPDX-License-Identifier: MIT
// Granular contacts across ranks: ghost velocities, species tables and polydisperse diameters
// give the same dynamics on 1, 2 and 4 ranks, and pair forces conserve momentum exactly.
#include <gtest/gtest.h>

#include <cmath>

#include "emergent/random.hpp"
#include "emergent/simulation.hpp"
#include "support/scene_fixture.hpp"

using namespace emergent;

namespace {

/// A dense, damped, frictional two-species granular gas in a periodic box (no gravity).
std::unique_ptr<Simulation> granular_gas(MPI_Comm comm) {
    RunSettings rs;
    rs.dt = 0.001;
    rs.skin = 0.3;
    auto sim = std::make_unique<Simulation>(comm, rs);
    Box box;
    box.hi = {9.6, 9.6, 9.6};
    sim->set_box(box);
    sim->set_species_masses({1.0, 3.4});
    GranularSettings g;
    g.n_species = 2;
    // Paper's drum values: gamma_s = 10 for big-big, 2 otherwise; mu proportional, max 0.5.
    g.pairs = {GranularPair{1000, 5, 2, 0.1}, GranularPair{1000, 5, 2, 0.1},
               GranularPair{1000, 5, 2, 0.1}, GranularPair{1000, 5, 10, 0.5}};
    g.max_diameter = 1.5;
    sim->add_force(make_granular_contacts(g));
    std::int64_t id = 0;
    for (int z = 0; z < 6; ++z)
        for (int y = 0; y < 6; ++y)
            for (int x = 0; x < 6; ++x, ++id) {
                const int species = uniform_open(3, id, 0) < 0.3 ? 1 : 0;
                const double d = (species ? 1.5 : 1.0) - 0.1 * uniform_open(3, id, 1);
                const Vec3 v{gaussian(5, id, 0), gaussian(5, id, 1), gaussian(5, id, 2)};
                sim->add_particle({0.8 + 1.6 * x, 0.8 + 1.6 * y, 0.8 + 1.6 * z}, v, species, id, d);
            }
    sim->initialise();
    return sim;
}

struct Trace {
    std::vector<double> kinetic;
    Vec3 momentum0{}, momentum1{};
    double momentum_scale = 0;
};

Trace run(MPI_Comm comm) {
    auto sim = granular_gas(comm);
    Trace t;
    t.momentum0 = sim->measure().momentum;
    for (int k = 1; k <= 500; ++k) {
        sim->step(k % 50 == 0);
        if (k % 50 == 0) t.kinetic.push_back(sim->measure().kinetic);
    }
    t.momentum1 = sim->measure().momentum;
    double scale = 0;
    const ParticleStore& s = sim->particles();
    for (std::size_t i = 0; i < s.n_owned(); ++i) scale += std::sqrt(dot(s.velocity[i], s.velocity[i]));
    MPI_Allreduce(&scale, &t.momentum_scale, 1, MPI_DOUBLE, MPI_SUM, comm);
    return t;
}

}  // namespace

TEST(GranularDecomposition, MomentumConserved) {
    const Trace decomposed = run(MPI_COMM_WORLD);
    // Damping and friction are pairwise and antisymmetric: total momentum changes only by
    // round-off (500 steps x ~1e-16 relative per pair force).
    const Vec3 dp = decomposed.momentum1 - decomposed.momentum0;
    EXPECT_LT(std::sqrt(dot(dp, dp)), 1e-11 * decomposed.momentum_scale);
}

// Run with several ranks only (ctest's 1-rank variant leaves out *RankCount* tests).
TEST(GranularDecomposition, SameDynamicsOnAnyRankCount) {
    const Trace decomposed = run(MPI_COMM_WORLD);
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank != 0) return;
    const Trace single = run(MPI_COMM_SELF);
    ASSERT_EQ(single.kinetic.size(), decomposed.kinetic.size());
    // Dissipative contacts damp rather than amplify differences; only summation order
    // differs, so 1e-9 relative is generous yet far below any missing ghost velocity (which
    // changes the damping forces at O(1)).
    for (std::size_t k = 0; k < single.kinetic.size(); ++k)
        EXPECT_TRUE(emergent::testing::relative_close(decomposed.kinetic[k], single.kinetic[k], 1e-9))
            << "sample " << k << ": " << decomposed.kinetic[k] << " vs " << single.kinetic[k];
    // The gas must actually have lost energy to the contacts, or the test checks nothing.
    EXPECT_LT(single.kinetic.back(), 0.9 * single.kinetic.front());
}

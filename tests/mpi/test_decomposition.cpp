// SPDX-License-Identifier: MIT
// Results do not depend on the rank count; particles survive many domain crossings.
// Run at 1, 2 and 4 ranks: the decomposed run on all ranks is compared with a one-rank run of
// the same input done on rank 0 alone (MPI_COMM_SELF) within the same job.
#include <gtest/gtest.h>

#include <algorithm>

#include "decomposition/rank_grid.hpp"
#include "emergent/random.hpp"
#include "support/scene_fixture.hpp"

using namespace emergent;
using emergent::testing::make_scene;
using emergent::testing::relative_close;

namespace {

std::vector<ThermoSample> trace(MPI_Comm comm, const std::vector<std::string>& sets, int steps) {
    auto sim = make_scene(comm, "lj-fluid", sets);
    std::vector<ThermoSample> out{sim->measure()};
    for (int k = 1; k <= steps; ++k) {
        sim->step(k % 20 == 0);
        if (k % 20 == 0) out.push_back(sim->measure());
    }
    return out;
}

int world_rank() {
    int r = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &r);
    return r;
}

void expect_same_thermodynamics(const std::vector<std::string>& sets) {
    const auto decomposed = trace(MPI_COMM_WORLD, sets, 200);
    if (world_rank() != 0) return;
    const auto single = trace(MPI_COMM_SELF, sets, 200);
    ASSERT_EQ(decomposed.size(), single.size());
    for (std::size_t k = 0; k < single.size(); ++k) {
        // Only the order of floating-point sums differs (~1e-16 per operation); over 200 steps
        // (1 tau) the chaotic growth of such differences (Lyapunov exponent of a few per tau)
        // keeps them near 1e-13, so 1e-10 leaves room while any real difference is >> 1e-6.
        EXPECT_EQ(decomposed[k].n, single[k].n);
        EXPECT_TRUE(relative_close(decomposed[k].potential, single[k].potential, 1e-10))
            << "step " << single[k].step << ": " << decomposed[k].potential << " vs "
            << single[k].potential;
        EXPECT_TRUE(relative_close(decomposed[k].kinetic, single[k].kinetic, 1e-10));
        EXPECT_TRUE(relative_close(decomposed[k].pressure, single[k].pressure, 1e-10));
    }
}

}  // namespace

TEST(Decomposition, NveThermodynamicsIndependentOfRankCount) {
    expect_same_thermodynamics({"n_cells=6", "thermostat=none"});
}

TEST(Decomposition, ThermostattedRunIndependentOfRankCount) {
    // The thermostat draws its random numbers from (seed, step), never per rank.
    expect_same_thermodynamics({"n_cells=6", "thermostat=bussi", "temperature=1.5"});
}

TEST(Decomposition, NoParticleLostUnderLargeUniformDrift) {
    auto sim = make_scene(MPI_COMM_WORLD, "lj-fluid", {"n_cells=6", "thermostat=none"});
    // Drift of (7, 5, 3) sigma/tau: over 4000 steps (20 tau) every particle travels ~170 sigma,
    // crossing each ~5 sigma wide domain dozens of times along every axis.
    for (Vec3& v : sim->particles().velocity) v += Vec3{7, 5, 3};
    sim->step(true);
    const double e0 = sim->measure().total;
    for (int k = 1; k <= 4000; ++k) sim->step(k % 1000 == 0);
    const ThermoSample end = sim->measure();
    EXPECT_EQ(end.n, 864);
    // Every id 0..N-1 present exactly once across ranks.
    std::vector<long long> count(864, 0);
    const ParticleStore& s = sim->particles();
    for (std::size_t i = 0; i < s.n_owned(); ++i) ++count.at(s.id[i]);
    MPI_Allreduce(MPI_IN_PLACE, count.data(), 864, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
    EXPECT_TRUE(std::all_of(count.begin(), count.end(), [](long long c) { return c == 1; }));
    // Galilean invariance: energy stays conserved in the moving frame (same bound reasoning as
    // the NVE test: fluctuations ~1e-3 per particle at N = 864).
    EXPECT_NEAR(end.total, e0, 3e-3);
    // And the drift itself is carried intact: momentum per particle stays (7, 5, 3).
    EXPECT_NEAR(end.momentum.x / end.n, 7.0, 1e-9);
    EXPECT_NEAR(end.momentum.z / end.n, 3.0, 1e-9);
}

TEST(Decomposition, MovedDomainPlanesTileTheBox) {
    // Planes placed unevenly (as load balance places them) on whatever grid this rank count
    // gets: every point of the box belongs to exactly one domain, the one rank_of names.
    Box box;
    box.hi = {12, 9, 7};
    decomp::RankGrid grid(MPI_COMM_WORLD, box);
    for (int d = 0; d < 3; ++d) {
        std::vector<double> planes = grid.cuts(d);
        const int n = grid.dims()[d];
        // Domain k gets a width proportional to k + 1.
        const double unit = box.hi[d] / (n * (n + 1) / 2.0);
        for (int k = 1; k < n; ++k) planes[k] = unit * k * (k + 1) / 2.0;
        grid.set_cuts(d, planes);
        EXPECT_DOUBLE_EQ(grid.lo()[d], planes[grid.coords()[d]]);
        EXPECT_DOUBLE_EQ(grid.hi()[d], planes[grid.coords()[d] + 1]);
    }
    int wrong = 0, owners_bad = 0;
    for (std::uint64_t k = 0; k < 2000; ++k) {
        // The same points on every rank: drawn from (seed, point, axis).
        const Vec3 x{12 * uniform_open(7, k, 0), 9 * uniform_open(7, k, 1), 7 * uniform_open(7, k, 2)};
        const bool mine = x.x >= grid.lo().x && x.x < grid.hi().x && x.y >= grid.lo().y &&
                          x.y < grid.hi().y && x.z >= grid.lo().z && x.z < grid.hi().z;
        if (mine != (grid.rank_of(x) == grid.rank())) ++wrong;
        int owners = mine;
        MPI_Allreduce(MPI_IN_PLACE, &owners, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
        owners_bad += owners != 1;
    }
    EXPECT_EQ(wrong, 0);
    EXPECT_EQ(owners_bad, 0);
    // Planes out of order are refused.
    if (grid.dims().x > 1) {
        std::vector<double> bad = grid.cuts(0);
        bad[1] = 13;
        EXPECT_THROW(grid.set_cuts(0, bad), std::logic_error);
    }
}

TEST(Decomposition, BalancedRunIndependentOfRankCount) {
    // Planes moved every 20 steps by the cost of each slab (here a fluid: small moves, but a
    // migration to new owners each time) change only the order of sums.
    expect_same_thermodynamics({"n_cells=6", "thermostat=none", "balance=cost", "balance.every=20"});
    auto sim = make_scene(MPI_COMM_WORLD, "lj-fluid",
                          {"n_cells=6", "thermostat=none", "balance=cost", "balance.every=20"});
    for (int k = 0; k < 100; ++k) sim->step(false);
    EXPECT_EQ(sim->load_balance().rebalances, 6);  // at the start and at steps 20, 40, ..., 100
    EXPECT_GE(sim->cost_imbalance(), 1.0);
}

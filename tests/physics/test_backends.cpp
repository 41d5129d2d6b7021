// SPDX-License-Identifier: MIT
// What a step moves between the host and the back end, counted by the execution layer on the
// checking back end (which moves exactly what a device back end would), and that the host back
// end moves nothing.
#include <gtest/gtest.h>

#include <cstdio>

#include "emergent/execution.hpp"
#include "support/scene_fixture.hpp"

using namespace emergent;
using emergent::testing::make_scene;

namespace {

struct StepTraffic {
    std::uint64_t plain_arrays = 0, plain_steps = 0, rebuild_arrays = 0, rebuilds = 0;
};

StepTraffic count_traffic(Simulation& sim, int steps) {
    StepTraffic t;
    for (int k = 0; k < steps; ++k) {
        const std::uint64_t before = exec::transfers().arrays;
        const long long built = sim.rebuilds();
        sim.step(false);
        const std::uint64_t moved = exec::transfers().arrays - before;
        if (sim.rebuilds() == built) {
            t.plain_arrays += moved;
            ++t.plain_steps;
        } else {
            t.rebuild_arrays += moved;
            ++t.rebuilds;
        }
    }
    return t;
}

}  // namespace

TEST(BackendTraffic, HostBackendMovesNothing) {
    auto sim = make_scene(MPI_COMM_SELF, "lj-fluid", {"n_cells=4", "backend=host"});
    const exec::Transfers before = exec::transfers();
    for (int k = 0; k < 50; ++k) sim->step(k % 10 == 0);
    sim->measure();
    EXPECT_EQ(exec::transfers().arrays, before.arrays);
}

TEST(BackendTraffic, StepWithoutSamplingOnTheCheckingBackend) {
    // WCA fluid with its Bussi thermostat, one rank. What still crosses on a step without
    // sampling or output: positions to the host for the rebuild test and the halo, then back
    // with the ghosts' new ones, and the forces the host's pair loop computed. Each part of the
    // step converted to the execution layer lowers these figures (and this test with them),
    // to none on a plain step.
    auto sim = make_scene(MPI_COMM_SELF, "lj-fluid", {"n_cells=5", "backend=checking"});
    for (int k = 0; k < 20; ++k) sim->step(false);
    const StepTraffic t = count_traffic(*sim, 200);
    ASSERT_GT(t.plain_steps, 100u);
    ASSERT_GT(t.rebuilds, 0u) << "the run should rebuild its list at least once";
    std::printf("arrays per plain step: %.2f; per step with a list rebuild: %.2f (%llu rebuilds)\n",
                double(t.plain_arrays) / t.plain_steps, double(t.rebuild_arrays) / t.rebuilds,
                static_cast<unsigned long long>(t.rebuilds));
    EXPECT_EQ(t.plain_arrays, 3 * t.plain_steps);
    // A rebuild (host code: migration, sorting, halo, list) needs every field on the host:
    // positions are there already for the test, velocities come back; it reorders and resizes
    // all, so the step's kernels get velocities, forces and species afresh, besides the
    // positions' two crossings of a plain step. Ids and images stay on the host.
    EXPECT_EQ(t.rebuild_arrays, 6 * t.rebuilds);
}

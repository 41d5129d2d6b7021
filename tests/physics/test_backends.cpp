// SPDX-License-Identifier: MIT
// What a step moves between the host and the back end, counted by the execution layer on the
// checking back end (which moves exactly what a device back end would), and that the host back
// end moves nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <utility>

#include "decomposition/halo_exchange.hpp"
#include "decomposition/migration.hpp"
#include "decomposition/rank_grid.hpp"
#include "emergent/error.hpp"
#include "emergent/execution.hpp"
#include "neighbour/backend_halo.hpp"
#include "particles/particle_mirror.hpp"
#include "neighbour/backend_list_build.hpp"
#include "neighbour/cell_list.hpp"
#include "support/scene_fixture.hpp"

using namespace emergent;
using emergent::testing::make_scene;

namespace {

struct StepTraffic {
    std::uint64_t plain_arrays = 0, plain_scalars = 0, plain_steps = 0, rebuild_arrays = 0,
                  rebuilds = 0;
    std::uint64_t rebuild_fewest = ~std::uint64_t{0}, rebuild_most = 0;  ///< arrays of one
    std::uint64_t rebuild_scalars_fewest = ~std::uint64_t{0}, rebuild_scalars_most = 0;
};

StepTraffic count_traffic(Simulation& sim, int steps) {
    StepTraffic t;
    for (int k = 0; k < steps; ++k) {
        const exec::Transfers before = exec::transfers();
        const long long built = sim.rebuilds();
        sim.step(false);
        const std::uint64_t moved = exec::transfers().arrays - before.arrays;
        if (sim.rebuilds() == built) {
            t.plain_arrays += moved;
            t.plain_scalars += exec::transfers().scalars - before.scalars;
            ++t.plain_steps;
        } else {
            t.rebuild_arrays += moved;
            ++t.rebuilds;
            t.rebuild_fewest = std::min(t.rebuild_fewest, moved);
            t.rebuild_most = std::max(t.rebuild_most, moved);
            const std::uint64_t scalars = exec::transfers().scalars - before.scalars;
            t.rebuild_scalars_fewest = std::min(t.rebuild_scalars_fewest, scalars);
            t.rebuild_scalars_most = std::max(t.rebuild_scalars_most, scalars);
        }
    }
    return t;
}

}  // namespace

/// The largest difference between two runs' forces on the same particle (matched by id), and
/// the largest force: (difference, scale).
std::pair<double, double> force_difference(const Simulation& a, const Simulation& b) {
    std::map<std::int64_t, Vec3> by_id;
    const ParticleStore& s = a.particles();
    for (std::size_t i = 0; i < s.n_owned(); ++i) by_id[s.id[i]] = s.force[i];
    const ParticleStore& t = b.particles();
    EXPECT_EQ(t.n_owned(), s.n_owned());
    double worst = 0, scale = 0;
    for (std::size_t i = 0; i < t.n_owned(); ++i) {
        const Vec3 d = t.force[i] - by_id.at(t.id[i]);
        worst = std::max(worst, std::sqrt(dot(d, d)));
        scale = std::max(scale, std::sqrt(dot(t.force[i], t.force[i])));
    }
    return {worst, scale};
}

TEST(BackendTraffic, HostBackendMovesNothing) {
    auto sim = make_scene(MPI_COMM_SELF, "lj-fluid", {"n_cells=4", "backend=host"});
    const exec::Transfers before = exec::transfers();
    for (int k = 0; k < 50; ++k) sim->step(k % 10 == 0);
    sim->measure();
    EXPECT_EQ(exec::transfers().arrays, before.arrays);
}

TEST(BackendTraffic, StepWithoutSamplingOnTheCheckingBackend) {
    // WCA fluid with its Bussi thermostat, one rank: a step without sampling or output moves no
    // particle array. It reads back one result: the largest displacement since the list was
    // built (the rebuild test) with the kinetic energy (the thermostat), reduced in the drift's
    // pass.
    auto sim = make_scene(MPI_COMM_SELF, "lj-fluid", {"n_cells=5", "backend=checking"});
    // Until the first list build after initialise: that one uploads what the host's build at
    // initialise left there only (ids, images); none after it moves an array.
    const long long initial = sim->rebuilds();
    for (int k = 0; k < 500 && sim->rebuilds() == initial; ++k) sim->step(false);
    ASSERT_GT(sim->rebuilds(), initial) << "the run should rebuild its list within 500 steps";
    const StepTraffic t = count_traffic(*sim, 200);
    ASSERT_GT(t.plain_steps, 100u);
    ASSERT_GT(t.rebuilds, 0u) << "the run should rebuild its list at least once";
    std::printf("per plain step: %.2f arrays, %.2f scalars; per step with a list rebuild: %.2f "
                "arrays, %llu-%llu scalars (%llu rebuilds)\n",
                double(t.plain_arrays) / t.plain_steps, double(t.plain_scalars) / t.plain_steps,
                double(t.rebuild_arrays) / t.rebuilds,
                static_cast<unsigned long long>(t.rebuild_scalars_fewest),
                static_cast<unsigned long long>(t.rebuild_scalars_most),
                static_cast<unsigned long long>(t.rebuilds));
    EXPECT_EQ(t.plain_arrays, 0u);
    EXPECT_EQ(t.plain_scalars, t.plain_steps);
    // The list is built where the particles live (BackendListBuild, one domain): no array
    // moves, and two results come back besides the step's one: the counts of every kind of
    // periodic image with the migration's first fault, and the list's length.
    EXPECT_EQ(t.rebuild_arrays, 0u);
    EXPECT_EQ(t.rebuild_scalars_fewest, 1u + 2u);
    EXPECT_EQ(t.rebuild_scalars_most, t.rebuild_scalars_fewest);
}

TEST(BackendForces, FullListOnTheBackendMatchesTheHostsHalfList) {
    // The same melted state: forces from the host's half list (Newton's third law, each pair
    // once) and from the back end's full list (each particle sums its own). Both add the same
    // pair terms in another order: agreement to round-off, ~1e-13 of the force scale for some
    // 50 neighbours; one missed or doubled pair would be off by O(1).
    const std::vector<std::string> common{"n_cells=5", "density=0.85", "thermostat=none", "seed=5"};
    auto with = [&](const char* backend, const char* layout) {
        std::vector<std::string> sets = common;
        sets.push_back(std::string("backend=") + backend);
        sets.push_back(std::string("neighbour_list=") + layout);
        auto sim = make_scene(MPI_COMM_SELF, "lj-fluid", sets);
        for (int k = 0; k < 100; ++k) sim->step(false);
        sim->step(true);
        return sim;
    };
    auto half = with("host", "half");
    auto full = with("checking", "full");
    const ThermoSample a = half->measure(), b = full->measure();
    EXPECT_NEAR(a.potential, b.potential, 1e-12 * std::abs(a.potential));
    EXPECT_NEAR(a.pressure, b.pressure, 1e-11 * std::abs(a.pressure));
    const auto [worst, scale] = force_difference(*half, *full);
    // 100 steps of chaotic dynamics first amplify the layouts' round-off difference (~1e-16
    // per step, Lyapunov time ~0.1 tau: 0.5 tau here, ~1e2 growth): still below 1e-11.
    std::printf("half vs full list after 100 steps: largest force difference %.3g of %.3g\n", worst, scale);
    EXPECT_LT(worst, 1e-11 * scale) << "largest force " << scale;
}

TEST(BackendTraffic, WallsAndWallLayersStayOnTheBackend) {
    // Thermal and specular walls (taylor-couette: cylinders and end plates), wall-layer
    // thermostats with gravity (rayleigh-benard), granular contacts with damping and friction on
    // a plane floor (granular-bed: ghost velocities too) on the checking back end, one rank.
    for (const char* scene : {"taylor-couette", "rayleigh-benard", "granular-bed"}) {
        auto sim = make_scene(MPI_COMM_SELF, scene, {"backend=checking"}, "tiny");
        // Past the first list build after initialise (it uploads what only the host had).
        const long long initial = sim->rebuilds();
        for (int k = 0; k < 10 || (k < 1000 && sim->rebuilds() == initial); ++k) sim->step(false);
        const StepTraffic t = count_traffic(*sim, 300);
        std::printf("%s: per plain step %.2f arrays, %.2f scalars; %llu rebuilds\n", scene,
                    double(t.plain_arrays) / t.plain_steps, double(t.plain_scalars) / t.plain_steps,
                    static_cast<unsigned long long>(t.rebuilds));
        ASSERT_GT(t.plain_steps, 150u) << scene;
        ASSERT_GT(t.rebuilds, 0u) << scene;
        // The list builds where the particles live (one rank, no bodies): the ids the walls
        // read are there already, and neither a step nor a rebuild moves an array.
        EXPECT_EQ(t.plain_arrays, 0u) << scene;
        EXPECT_EQ(t.rebuild_arrays, 0u) << scene;
    }
}

TEST(BackendForces, GranularFullListMatchesTheHostsHalfList) {
    // Spheres settling on a floor with damping and friction: contact forces and plane-wall
    // forces from the host's half list (Newton's third law) and from the back end's full list
    // (each sphere sums its own), after the same 600 steps from the same start (the spheres have reached the floor). The same
    // contact law, summed in another order: round-off, grown little over 600 steps (a friction
    // cap switching between the runs would show as an O(1) difference); a wrong sign, a missed
    // or doubled contact would be O(1) too.
    auto with = [](const char* backend, const char* layout) {
        auto sim = make_scene(MPI_COMM_SELF, "granular-bed",
                              {std::string("backend=") + backend, std::string("neighbour_list=") + layout},
                              "tiny");
        for (int k = 0; k < 599; ++k) sim->step(false);
        sim->step(true);
        return sim;
    };
    auto half = with("host", "half");
    auto full = with("checking", "full");
    const ThermoSample a = half->measure(), b = full->measure();
    ASSERT_GT(a.max_overlap, 0) << "no contacts yet: the comparison would test nothing";
    EXPECT_NEAR(a.max_overlap, b.max_overlap, 1e-9);
    EXPECT_NEAR(a.potential, b.potential, 1e-9 * std::abs(a.potential));
    const auto [worst, scale] = force_difference(*half, *full);
    std::printf("granular half vs full list: largest force difference %.3g of %.3g\n", worst, scale);
    EXPECT_LT(worst, 1e-9 * scale);
}

TEST(BackendTraffic, RigidBodiesStayOnTheBackend) {
    // Rigid bodies (the drum's tetrahedra with their rough wall; capsomers with sites in an
    // explicit solvent under the solvent-only thermostat, and in the implicit solvent's Langevin
    // dynamics) on the checking back end, one rank, full list: the bodies' force and torque
    // sums, kicks, drifts, free rotations and Langevin updates run there, and so does the list
    // build (constituents dropped, bodies brought home, constituents placed again), so neither
    // a step without sampling nor a list rebuild moves an array.
    const std::vector<std::vector<std::string>> runs{
        {"rotating-drum"}, {"capsid-assembly", "start=monomers", "attraction=0.09"},
        {"capsid-assembly", "start=monomers", "solvent=implicit", "friction_translation=1"}};
    for (const auto& run : runs) {
        std::vector<std::string> sets(run.begin() + 1, run.end());
        sets.push_back("backend=checking");
        sets.push_back("neighbour_list=full");
        auto sim = make_scene(MPI_COMM_SELF, run[0], sets, "tiny");
        // Past the first list build after initialise (it uploads what only the host had).
        const long long initial = sim->rebuilds();
        for (int k = 0; k < 10 || (k < 1000 && sim->rebuilds() == initial); ++k) sim->step(false);
        const StepTraffic t = count_traffic(*sim, 200);
        std::printf("%s %s: per plain step %.2f arrays, %.2f scalars; per rebuild %.2f arrays (%llu)\n",
                    run[0].c_str(), sets.front().c_str(), double(t.plain_arrays) / t.plain_steps,
                    double(t.plain_scalars) / t.plain_steps, double(t.rebuild_arrays) / std::max<std::uint64_t>(1, t.rebuilds),
                    static_cast<unsigned long long>(t.rebuilds));
        ASSERT_GT(t.plain_steps, 20u) << run[0];
        ASSERT_GT(t.rebuilds, 0u) << run[0];
        EXPECT_EQ(t.plain_arrays, 0u) << run[0];
        EXPECT_EQ(t.rebuild_arrays, 0u) << run[0];
    }
}

TEST(BackendListBuild, NamesAParticleThatCannotComeHomeAsTheHostsMigrationDoes) {
    // A box closed along y: two particles left through the closed faces, one of them after
    // crossing the periodic x face too. The host's migration and the back end's build name the
    // same particle, at the same (wrapped) position, in the same words.
    Box box;
    box.hi = {10, 10, 10};
    box.periodic[1] = false;
    decomp::RankGrid grid(MPI_COMM_SELF, box);
    ParticleStore start;
    const Vec3 places[] = {{1, 1, 1}, {10.25, 10.5, 2}, {5, 5, 5}, {9, 2, 3}, {4, -0.5, 4}};
    const std::int64_t ids[] = {0, 3, 1, 2, 7};
    for (int k = 0; k < 5; ++k) start.add_owned(places[k], {0.5, 0, 0}, 0, ids[k]);
    std::string host_says;
    {
        ParticleStore s = start;
        decomp::Migration migration;
        try {
            migration.apply(s, grid);
        } catch (const InstabilityError& e) {
            host_says = e.what();
        }
    }
    ASSERT_EQ(host_says, "particle id 3 at (0.25, 10.5, 2) left the region through a closed boundary along y");
    ParticleStore s = start;
    exec::ParticleMirror mirror(exec::separate_host_memory(), true);
    CellList cells;
    cells.setup(grid.lo(), grid.hi(), 2.0, 2.0);
    decomp::HaloExchange halo;
    exec::BackendHalo backend_halo;
    BackendListBuild list_build;
    const exec::Target checking{false, true, nullptr};
    ASSERT_TRUE(list_build.build(checking, mirror, s, grid, cells, 2.0, 2.0, halo, backend_halo));
    EXPECT_EQ(list_build.fault(), host_says);
}

namespace {

/// A one-rank build on the host's way (Neighbourhood::build without bodies): migration, cell
/// order, halo; and on the back end's (BackendListBuild), from the same particles. Both
/// stores, and both halos' plans.
struct BothBuilds {
    ParticleStore host, backend;
    decomp::HaloExchange host_halo, backend_halo;
    bool built = false;
};

BothBuilds build_both(const Box& box, const ParticleStore& start, double width) {
    BothBuilds b;
    decomp::RankGrid grid(MPI_COMM_SELF, box);
    CellList cells;
    cells.setup(grid.lo(), grid.hi(), width, width);
    b.host = start;
    decomp::Migration migration;
    migration.apply(b.host, grid);
    std::vector<std::uint32_t> order;
    cells.sort_order(b.host.position.data(), b.host.id.data(), b.host.n_owned(), order);
    b.host.permute_owned(order);
    b.host_halo.build(b.host, grid, width, kAllFields & ~kForce);

    b.backend = start;
    exec::ParticleMirror mirror(exec::separate_host_memory(), true);
    exec::BackendHalo refresh;
    BackendListBuild list_build;
    const exec::Target checking{false, true, nullptr};
    b.built = list_build.build(checking, mirror, b.backend, grid, cells, width, width, b.backend_halo, refresh);
    EXPECT_EQ(list_build.fault(), "");
    mirror.to_host(b.backend, kAllFields & ~kForce);
    return b;
}

}  // namespace

TEST(BackendListBuild, OneDomainMakesTheHostsOwnersGhostsAndPlanBitForBit) {
    // One rank: the back end images every particle once per kind of image (faces, edges,
    // corners) in one pass; the host's halo swaps face after face. The same particles, order,
    // fields and bits must come out, and the same import range for every swap: in a box
    // periodic in x and y and walled in z, and in one so small (4 across, ghost width 2.5)
    // that a particle lies near both faces of an axis. Some particles start outside a periodic
    // face (they come home), some on a face, some with coordinates of -0.
    for (const double side : {10.0, 4.0}) {
        Box box;
        box.hi = {side, side, side};
        box.periodic[2] = false;
        std::uint64_t state = 99;
        auto uniform = [&state] {
            state = state * 6364136223846793005ull + 1442695040888963407ull;
            return double(state >> 11) * 0x1.0p-53;
        };
        ParticleStore start;
        for (int k = 0; k < 300; ++k) {
            Vec3 x{side * (1.1 * uniform() - 0.05), side * uniform(), side * uniform()};
            if (k % 13 == 0) x.y = -0.0;
            if (k % 17 == 0) x = {side, 0.0, side * 0.5};  // on the x face: wraps to 0
            start.add_owned(x, {uniform() - 0.5, -0.0, uniform()}, k % 3, 1000 - 3 * k);
        }
        const BothBuilds b = build_both(box, start, 2.5);
        ASSERT_TRUE(b.built) << side;
        ASSERT_EQ(b.backend.n_owned(), b.host.n_owned()) << side;
        ASSERT_EQ(b.backend.size(), b.host.size()) << side;
        ASSERT_GT(b.host.n_ghost(), b.host.n_owned() / 4) << side;
        std::size_t differing = 0;
        for (std::size_t i = 0; i < b.host.size(); ++i) {
            differing += std::memcmp(&b.host.position[i], &b.backend.position[i], sizeof(Vec3)) != 0;
            differing += std::memcmp(&b.host.velocity[i], &b.backend.velocity[i], sizeof(Vec3)) != 0;
            differing += b.host.id[i] != b.backend.id[i] || b.host.species[i] != b.backend.species[i];
            differing += std::memcmp(&b.host.image[i], &b.backend.image[i], sizeof(Int3)) != 0;
        }
        EXPECT_EQ(differing, 0u) << side;
        const decomp::HaloPlan &on_backend = b.backend_halo.plan(), &on_host = b.host_halo.plan();
        ASSERT_EQ(on_backend.swaps.size(), on_host.swaps.size());
        EXPECT_EQ(on_backend.n_owned, on_host.n_owned);
        EXPECT_EQ(on_backend.n_ghost, on_host.n_ghost);
        for (std::size_t k = 0; k < on_host.swaps.size(); ++k) {
            EXPECT_EQ(on_backend.swaps[k].import_first, on_host.swaps[k].import_first) << k;
            EXPECT_EQ(on_backend.swaps[k].import_count, on_host.swaps[k].import_count) << k;
            EXPECT_EQ(on_backend.swaps[k].export_count, on_host.swaps[k].export_count) << k;
        }
    }
}

TEST(BackendListBuild, OneDomainLeavesAnIdNoKeyHoldsToTheHost) {
    // Ids of 2^32 and more are allowed but fit no sort key: the back end's build declines
    // (returns false) and the host builds.
    Box box;
    box.hi = {10, 10, 10};
    ParticleStore start;
    start.add_owned({1, 1, 1}, {0, 0, 0}, 0, 5);
    start.add_owned({2, 2, 2}, {0, 0, 0}, 0, std::int64_t{1} << 32);
    decomp::RankGrid grid(MPI_COMM_SELF, box);
    CellList cells;
    cells.setup(grid.lo(), grid.hi(), 2.0, 2.0);
    exec::ParticleMirror mirror(exec::separate_host_memory(), true);
    decomp::HaloExchange halo;
    exec::BackendHalo refresh;
    BackendListBuild list_build;
    const exec::Target checking{false, true, nullptr};
    ParticleStore s = start;
    EXPECT_FALSE(list_build.build(checking, mirror, s, grid, cells, 2.0, 2.0, halo, refresh));
    EXPECT_EQ(list_build.fault(), "");
}

TEST(BackendHalo, RefreshFromRootsGivesTheSwapsBits) {
    // One rank, periodic box: the back end refreshes every ghost from its owned root in one
    // pass. Its positions and velocities must be bit for bit those of the swaps one after
    // another (the host's refresh), signs of zero included: corner ghosts are shifted along
    // three axes, and velocities of -0 pass through a swap's zero shift as +0.
    Box box;
    box.hi = {10, 10, 10};
    decomp::RankGrid grid(MPI_COMM_SELF, box);
    ParticleStore start;
    std::uint64_t state = 12345;
    auto uniform = [&state] {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return double(state >> 11) * 0x1.0p-53;
    };
    for (int k = 0; k < 400; ++k) {
        Vec3 x{10 * uniform(), 10 * uniform(), 10 * uniform()};
        Vec3 v{uniform() - 0.5, uniform() - 0.5, uniform() - 0.5};
        if (k % 7 == 0) x.y = -0.0, v.x = -0.0;
        if (k % 11 == 0) x = {9.999, 0.001, 9.999};
        start.add_owned(x, v, 0, k);
    }
    decomp::HaloExchange halo;
    halo.build(start, grid, 2.5, kPosition | kVelocity);
    ASSERT_TRUE(halo.plan().from_roots());
    ASSERT_GT(halo.n_ghost(), start.n_owned() / 2);
    // The owners move; then each side refreshes its ghosts.
    for (std::size_t i = 0; i < start.n_owned(); ++i)
        start.position[i] += Vec3{0.01 * uniform(), -0.01 * uniform(), 0.02 * uniform()};
    ParticleStore by_swaps = start, by_roots = start;
    halo.gather_positions(by_swaps);
    halo.gather_velocities(by_swaps);

    exec::ParticleMirror mirror(exec::separate_host_memory(), true);
    const exec::Target checking{false, true, nullptr};
    mirror.to_backend(by_roots, kPosition | kVelocity);
    exec::BackendHalo backend_halo;
    backend_halo.place(halo, mirror, 0);
    backend_halo.gather(checking, halo, mirror, mirror.array<Vec3>(kPosition), true, 0);
    backend_halo.gather(checking, halo, mirror, mirror.array<Vec3>(kVelocity), false, 0);
    mirror.written_on_backend(by_roots, kPosition | kVelocity);
    mirror.to_host(by_roots, kPosition | kVelocity);
    ASSERT_EQ(by_roots.size(), by_swaps.size());
    std::size_t differing = 0;
    for (std::size_t i = by_swaps.n_owned(); i < by_swaps.size(); ++i)
        for (int d = 0; d < 3; ++d) {
            const double a[2] = {by_swaps.position[i][d], by_swaps.velocity[i][d]};
            const double b[2] = {by_roots.position[i][d], by_roots.velocity[i][d]};
            differing += std::memcmp(a, b, sizeof a) != 0;
        }
    EXPECT_EQ(differing, 0u);
}

// SPDX-License-Identifier: MIT
// Coarse-graining recovers known flow, temperature and density fields from synthetic particles.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "emergent/random.hpp"
#include "emergent/execution.hpp"
#include "neighbour/list_build_loops.hpp"
#include "observe/field_accumulator.hpp"
#include "observe/field_sampling.hpp"

using namespace emergent;

namespace {
/// Particles uniform in [0, L)^3 with velocity u(x) + Maxwell noise at temperature T (m = 1).
/// Closed box: the synthetic particles are never outside it.
Box closed_box(double L) {
    Box b;
    b.hi = {L, L, L};
    b.periodic[0] = b.periodic[1] = b.periodic[2] = false;
    return b;
}

template <class Flow>
void fill(ParticleStore& s, int n, double L, double T, std::uint64_t seed, Flow flow) {
    s.resize_owned(0);
    for (int i = 0; i < n; ++i) {
        const Vec3 x{L * uniform_open(seed, i, 0), L * uniform_open(seed, i, 1),
                     L * uniform_open(seed, i, 2)};
        Vec3 v = flow(x);
        for (int d = 0; d < 3; ++d) v[d] += std::sqrt(T) * gaussian(seed, i, 3 + d);
        s.add_owned(x, v, 0, i);
    }
}
}  // namespace

TEST(FieldAccumulator, UniformFlowGivesFlowAndTemperatureInEveryCell) {
    const double L = 10, T = 1.5, rho = 0.8;
    const int n = static_cast<int>(rho * L * L * L);
    FieldGrid grid;
    grid.n = {2, 2, 5};
    grid.hi = {L, L, L};
    FieldAccumulator acc(grid);
    const Box box = closed_box(L);
    ParticleStore s;
    const int samples = 40;
    for (int k = 0; k < samples; ++k) {
        fill(s, n, L, T, 100 + k, [](const Vec3&) { return Vec3{0.7, -0.2, 0.1}; });
        acc.add(s, {1.0}, box);
    }
    const FieldFrame f = acc.take(MPI_COMM_SELF);
    for (int c = 0; c < grid.n_cells(); ++c) {
        const double count = f.count[c];  // ~ 40 * 800 / 20 = 1600 samples per cell
        // Standard error of a cell mean: sqrt(T / count) ~ 0.03; of T: T sqrt(2 / (3 count))
        // ~ 0.03. Five standard errors: a false alarm is ~1e-6 per cell.
        const double se_u = std::sqrt(T / count), se_t = T * std::sqrt(2.0 / (3 * count));
        EXPECT_NEAR(f.velocity[3 * c + 0], 0.7, 5 * se_u);
        EXPECT_NEAR(f.velocity[3 * c + 1], -0.2, 5 * se_u);
        EXPECT_NEAR(f.velocity[3 * c + 2], 0.1, 5 * se_u);
        EXPECT_NEAR(f.temperature[c], T, 5 * se_t);
        // Density: Poisson counts, relative error 1/sqrt(count).
        EXPECT_NEAR(f.density[c], rho, 5 * rho / std::sqrt(count));
    }
    EXPECT_EQ(acc.samples(), 0);  // take() restarts the interval
}

TEST(FieldAccumulator, LinearShearProfileIsRecovered) {
    const double L = 12, T = 1.0, rate = 0.25;
    FieldGrid grid;
    grid.n = {1, 1, 12};  // slabs along z
    grid.hi = {L, L, L};
    FieldAccumulator acc(grid);
    const Box box = closed_box(L);
    ParticleStore s;
    for (int k = 0; k < 30; ++k) {
        fill(s, 1400, L, T, 500 + k, [&](const Vec3& x) { return Vec3{rate * (x.z - L / 2), 0, 0}; });
        acc.add(s, {1.0}, box);
    }
    const FieldFrame f = acc.take(MPI_COMM_SELF);
    for (int c = 0; c < 12; ++c) {
        const double z = (c + 0.5) * L / 12;
        const double se = std::sqrt(T / f.count[c]);
        EXPECT_NEAR(f.velocity[3 * c], rate * (z - L / 2), 5 * se) << "slab " << c;
        // Within a slab the flow varies by rate * dz = 0.25 across the slab: a variance of
        // (rate dz)^2 / 12 ~ 0.005 adds to the fluctuations, inside the tolerance.
        EXPECT_NEAR(f.temperature[c], T, 5 * T * std::sqrt(2.0 / (3 * f.count[c])) + 0.006);
    }
}

TEST(FieldAccumulator, CylindricalCellsHaveTheRightVolumeAndRotation) {
    // Solid-body rotation about the z axis through (5, 5): u = omega z^ x r. Density is uniform,
    // which checks the cell volumes; since u is linear in x, a cell's mean flow equals the flow
    // at the cell's mean particle position, which the test computes independently.
    const double L = 10, T = 1.0, omega = 0.3;
    FieldGrid grid;
    grid.kind = FieldGrid::Kind::Cylindrical;
    grid.axis = 2;
    grid.lo = {5, 5, 0};
    grid.hi = {5, 5, L};
    grid.r_min = 1;
    grid.r_max = 5;
    grid.n = {4, 6, 1};  // 4 rings x 6 sectors
    auto flow = [&](const Vec3& x) { return Vec3{-omega * (x.y - 5), omega * (x.x - 5), 0}; };
    FieldAccumulator acc(grid);
    const Box box = closed_box(L);
    ParticleStore s;
    std::vector<double> mean_r(grid.n_cells(), 0);
    std::vector<double> hits(grid.n_cells(), 0);
    for (int k = 0; k < 60; ++k) {
        fill(s, 800, L, T, 900 + k, flow);
        acc.add(s, {1.0}, box);
        for (std::size_t i = 0; i < s.n_owned(); ++i) {
            const int c = grid.cell_of(s.position[i]);
            const Vec3 r = s.position[i] - Vec3{5, 5, s.position[i].z};
            if (c >= 0) mean_r[c] += std::sqrt(dot(r, r)), hits[c] += 1;
        }
    }
    const FieldFrame f = acc.take(MPI_COMM_SELF);
    for (int c = 0; c < grid.n_cells(); ++c) {
        ASSERT_EQ(f.count[c], hits[c]);
        EXPECT_NEAR(f.density[c], 0.8, 5 * 0.8 / std::sqrt(f.count[c])) << "cell " << c;
        // Components are (r, theta, z): no radial flow, swirl omega r at the cell's mean radius.
        const double se = std::sqrt(T / f.count[c]);
        EXPECT_NEAR(f.velocity[3 * c], 0.0, 5 * se) << "cell " << c;
        EXPECT_NEAR(f.velocity[3 * c + 1], omega * mean_r[c] / hits[c], 5 * se) << "cell " << c;
        EXPECT_NEAR(f.velocity[3 * c + 2], 0.0, 5 * se) << "cell " << c;
    }
}

TEST(FieldAccumulator, ParticlesJustPastAPeriodicFaceAreCounted) {
    // Between list builds owned particles may lie a little outside the periodic box; one a
    // hair below lo wraps to exactly hi in floating point, which no cell holds.
    Box box;
    box.hi = {10, 10, 10};
    FieldGrid grid;
    grid.n = {2, 1, 1};
    grid.hi = box.hi;
    FieldAccumulator acc(grid);
    ParticleStore s;
    s.add_owned({-1e-17, 5, 5}, {1, 0, 0}, 0, 0);  // -1e-17 + 10 == 10 in double
    s.add_owned({10.25, 5, 5}, {1, 0, 0}, 0, 1);   // past hi: the first cell
    s.add_owned({-0.5, 5, 5}, {1, 0, 0}, 0, 2);    // below lo: the last cell
    acc.add(s, {1.0}, box);
    const FieldFrame f = acc.take(MPI_COMM_SELF);
    EXPECT_EQ(f.count[0] + f.count[1], 3);
    EXPECT_EQ(f.count[0], 2);  // -1e-17 lands at lo, 10.25 at 0.25
    EXPECT_EQ(f.count[1], 1);
}

TEST(FieldAccumulator, SumsByCellOrderEqualTheHostsScatterBitForBit) {
    // The back end's sample (particles sorted stably by cell, each cell's members summed in
    // index order: observe::FieldCellKey, FieldCellSums through the execution layer) against
    // the host's scatter in index order: the same additions, so the same bits. The grids: the
    // whole periodic box, a thin slab that most particles miss (tested on its z extent first),
    // and a cylindrical shell (the other branch of FieldGrid::cell_of).
    Box box;
    box.hi = {12, 12, 12};
    ParticleStore s;
    fill(s, 3000, 12, 1.5, 7, [](const Vec3& x) { return Vec3{0.1 * x.z, 0, 0.05 * x.x}; });
    for (std::size_t i = 0; i < s.n_owned(); i += 7) s.position[i].x -= 12.2;  // past a face
    FieldGrid whole;
    whole.n = {3, 3, 4};
    whole.hi = box.hi;
    FieldGrid slab;
    slab.n = {6, 6, 1};
    slab.lo = {0, 0, 3.5};
    slab.hi = {12, 12, 4.5};
    FieldGrid shell;
    shell.kind = FieldGrid::Kind::Cylindrical;
    shell.n = {3, 4, 2};
    shell.lo = {6, 6, 0};
    shell.hi = {6, 6, 12};
    shell.r_min = 1;
    shell.r_max = 5;
    const std::vector<double> mass{1.0};
    const std::size_t n = s.n_owned();
    int g = 0;
    for (const FieldGrid& grid : {whole, slab, shell}) {
        const std::size_t cells = static_cast<std::size_t>(grid.n_cells());
        std::vector<double> scattered(cells * observe::kFieldSums), by_cell(cells * observe::kFieldSums);
        observe::scatter_field_sums(grid, box, n, s.position.data(), s.velocity.data(), s.species.data(),
                                    mass.data(), scattered.data());
        std::vector<std::uint32_t> key(n), member(n), start(cells + 1);
        exec::for_each(exec::Host{}, n, observe::FieldCellKey{grid, box, s.position.data(), key.data(), member.data()});
        exec::sort_pairs(exec::Host{}, key.data(), member.data(), n);
        exec::for_each(exec::Host{}, cells + 1, build::CellStart{key.data(), n, start.data()});
        exec::for_each(exec::Host{}, cells,
                       observe::FieldCellSums{grid, box, s.position.data(), s.velocity.data(), s.species.data(),
                                              mass.data(), start.data(), member.data(), by_cell.data()});
        EXPECT_EQ(0, std::memcmp(scattered.data(), by_cell.data(), scattered.size() * sizeof(double))) << "grid " << g;
        double counted = 0;
        for (std::size_t c = 0; c < cells; ++c) counted += scattered[c * observe::kFieldSums];
        // Every particle is in the whole box's grid; the slab holds about 1/12 of them.
        if (g == 0) EXPECT_EQ(counted, 3000);
        if (g == 1) {
            EXPECT_GT(counted, 150);
            EXPECT_LT(counted, 350);
        }
        ++g;
    }
}

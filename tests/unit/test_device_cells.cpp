// SPDX-License-Identifier: MIT
// The GPU path's neighbour search (Z-order cell sort, cell ranges, strided full list) and its
// pair functor, run through the host back end and checked against all pairs: the same
// functors the device runs, so their logic is verified on machines without a GPU.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <set>

#include "emergent/execution.hpp"
#include "force/lennard_jones.hpp"
#include "force/pair_full_list.hpp"
#include "gpu/device_cells.hpp"
#include "support/fluid_start.hpp"

using namespace emergent;

namespace {

struct HostList {
    gpu::CellGrid grid;
    force::MinimumImage image;
    std::vector<Vec3> x;
    std::vector<std::uint32_t> id, count, index;
    std::uint32_t capacity;
};

/// The device's rebuild sequence on the host (std::stable_sort stands in for the radix sort).
HostList build(const fixtures::FluidStart& s, double list_cutoff, std::uint32_t capacity) {
    HostList h;
    const std::size_t n = s.x.size();
    for (int d = 0; d < 3; ++d) {
        h.grid.n[d] = static_cast<int>(std::floor(s.box[d] / list_cutoff));
        h.grid.inverse_width[d] = h.grid.n[d] / s.box[d];
        h.image.length[d] = s.box[d];
        h.image.inverse[d] = 1 / s.box[d];
    }
    std::vector<Vec3> x = s.x;
    std::vector<Int3> img(n, Int3{0, 0, 0});
    exec::for_each(exec::Host{}, n, gpu::WrapIntoBox{x.data(), img.data(), s.box});
    std::vector<std::uint32_t> key(n), order(n);
    exec::for_each(exec::Host{}, n, gpu::CellKey{x.data(), h.grid, key.data(), order.data()});
    std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) { return key[a] < key[b]; });
    std::vector<std::uint32_t> key_sorted(n), ids(n);
    std::iota(ids.begin(), ids.end(), 0u);
    h.x.resize(n);
    h.id.resize(n);
    exec::for_each(exec::Host{}, n, gpu::Gather<std::uint32_t>{key.data(), key_sorted.data(), order.data()});
    exec::for_each(exec::Host{}, n, gpu::Gather<Vec3>{x.data(), h.x.data(), order.data()});
    exec::for_each(exec::Host{}, n, gpu::Gather<std::uint32_t>{ids.data(), h.id.data(), order.data()});
    std::vector<std::uint32_t> start(h.grid.cells(), 0), end(h.grid.cells(), 0);
    exec::for_each(exec::Host{}, n, gpu::CellRanges{h.x.data(), key_sorted.data(), n, h.grid, start.data(), end.data()});
    h.capacity = capacity;
    h.count.assign(n, 0);
    h.index.assign(std::size_t(capacity) * n, 0xffffffffu);
    exec::for_each(exec::Host{}, n,
                   gpu::BuildFullList{h.x.data(), h.grid, start.data(), end.data(), h.image,
                                      list_cutoff * list_cutoff, capacity, n, h.count.data(), h.index.data()});
    return h;
}

}  // namespace

TEST(DeviceCells, MortonKeyInterleavesTheCellCoordinates) {
    gpu::CellGrid g;
    g.n = {8, 8, 8};
    EXPECT_EQ(g.morton({1, 0, 0}), 1u);
    EXPECT_EQ(g.morton({0, 1, 0}), 2u);
    EXPECT_EQ(g.morton({0, 0, 1}), 4u);
    EXPECT_EQ(g.morton({7, 7, 7}), 511u);
    EXPECT_EQ(g.morton({1023, 0, 0}), 0x09249249u);
    EXPECT_EQ(g.key_bits(), 9);
}

TEST(DeviceCells, FullListHoldsExactlyThePairsWithinTheListCutoff) {
    // 1372 atoms, rho 0.8, the lattice jittered: every pair within 1.42 at nearest image.
    const auto s = fixtures::fcc_fluid(7, 0.8, 1.0, 0.3, 9);
    const double list_cutoff = 1.42;
    const HostList h = build(s, list_cutoff, 64);
    const std::size_t n = s.x.size();
    // The cell sort is a permutation and keeps every particle in its cell.
    std::set<std::uint32_t> seen(h.id.begin(), h.id.end());
    EXPECT_EQ(seen.size(), n);
    std::size_t listed = 0;
    for (std::size_t i = 0; i < n; ++i) {
        std::set<std::uint32_t> expected;
        for (std::size_t j = 0; j < n; ++j) {
            if (j == i) continue;
            const Vec3 d = h.image(h.x[i] - h.x[j]);
            if (dot(d, d) < list_cutoff * list_cutoff) expected.insert(static_cast<std::uint32_t>(j));
        }
        ASSERT_LE(h.count[i], h.capacity);
        std::set<std::uint32_t> got;
        for (std::uint32_t k = 0; k < h.count[i]; ++k) got.insert(h.index[k * n + i]);
        ASSERT_EQ(got, expected) << "particle " << i;
        listed += h.count[i];
    }
    EXPECT_GT(listed, 10 * n);  // ~ (4/3) pi 1.42^3 0.8 = 9.6 per atom; jitter adds some
}

TEST(DeviceCells, CountsBeyondTheCapacityWithoutWritingPastIt) {
    const auto s = fixtures::fcc_fluid(5, 0.8, 1.0, 0.3, 9);
    const HostList h = build(s, 1.42, 4);
    const std::size_t n = s.x.size();
    EXPECT_GT(*std::max_element(h.count.begin(), h.count.end()), 4u);
    EXPECT_EQ(h.index.size(), 4 * n);  // nothing resized, and every slot is a valid index
    for (std::uint32_t j : h.index) EXPECT_LT(j, n);
}

TEST(DeviceCells, StridedNearestImageForcesMatchAllPairs) {
    const auto s = fixtures::fcc_fluid(6, 0.8, 1.0, 0.3, 21);
    const double rc = 2.5;
    const HostList h = build(s, rc + 0.3, 128);
    const std::size_t n = s.x.size();
    const force::LennardJones lj({1.0, 1.0, rc});
    std::vector<Vec3> f(n);
    std::vector<Real> e(n), w(n);
    force::PairForceFullList<force::LennardJones, force::StridedNeighbours, force::MinimumImage, true> pf{
        h.x.data(), f.data(), {h.count.data(), h.index.data(), n}, lj, h.image, e.data(), w.data()};
    exec::for_each(exec::Host{}, n, pf);
    double worst = 0, scale = 0, energy = 0, ref_energy = 0;
    for (std::size_t i = 0; i < n; ++i) {
        Vec3 ref{0, 0, 0};
        for (std::size_t j = 0; j < n; ++j) {
            if (j == i) continue;
            const Vec3 d = h.image(h.x[i] - h.x[j]);
            const double r2 = dot(d, d);
            if (r2 >= rc * rc) continue;
            ref += lj.force_over_r(r2) * d;
            ref_energy += 0.5 * lj.energy(r2);
        }
        const Vec3 diff = f[i] - ref;
        worst = std::max(worst, std::sqrt(dot(diff, diff)));
        scale = std::max(scale, std::sqrt(dot(ref, ref)));
        energy += e[i];
    }
    // Same terms in another order: round-off only.
    EXPECT_LT(worst, 1e-12 * scale);
    EXPECT_NEAR(energy, ref_energy, 1e-12 * std::abs(ref_energy));

    // Mixed mode: float pair arithmetic from a double separation, double sums. Float's
    // relative precision is 6e-8; the largest terms of a force sum partly cancel, so allow 1e-5
    // of the largest force, still far below a wrong pair.
    force::PairForceFullList<force::LennardJonesT<float>, force::StridedNeighbours, force::MinimumImage> mixed{
        h.x.data(), f.data(), {h.count.data(), h.index.data(), n}, lj.as<float>(), h.image};
    std::vector<Vec3> fd(n);
    force::PairForceFullList<force::LennardJones, force::StridedNeighbours, force::MinimumImage> dbl{
        h.x.data(), fd.data(), {h.count.data(), h.index.data(), n}, lj, h.image};
    exec::for_each(exec::Host{}, n, mixed);
    exec::for_each(exec::Host{}, n, dbl);
    double mixed_worst = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3 diff = f[i] - fd[i];
        mixed_worst = std::max(mixed_worst, std::sqrt(dot(diff, diff)));
    }
    EXPECT_LT(mixed_worst, 1e-5 * scale);
    EXPECT_GT(mixed_worst, 0);  // it really ran in float
}

TEST(DeviceCells, WrapCountsImages) {
    Vec3 x[2] = {{-0.5, 10.25, 3}, {21.5, -10.5, 9.999}};
    Int3 img[2] = {{0, 0, 0}, {1, 0, -2}};
    exec::for_each(exec::Host{}, 2, gpu::WrapIntoBox{x, img, {10, 10, 10}});
    EXPECT_DOUBLE_EQ(x[0].x, 9.5);
    EXPECT_EQ(img[0].x, -1);
    EXPECT_DOUBLE_EQ(x[0].y, 0.25);
    EXPECT_EQ(img[0].y, 1);
    EXPECT_DOUBLE_EQ(x[1].x, 1.5);
    EXPECT_EQ(img[1].x, 3);
    EXPECT_DOUBLE_EQ(x[1].y, 9.5);
    EXPECT_EQ(img[1].y, -2);
    EXPECT_EQ(img[1].z, -2);  // inside: untouched
}

TEST(DeviceCells, EndOfStepCheckFlagsRebuildsAndNonFiniteStates) {
    const double nan = std::nan("");
    Vec3 x[3] = {{1, 1, 1}, {2, 2, 2}, {3, 3, 3}};
    Vec3 v[3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    Vec3 f[3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    const Vec3 x_build[3] = {{1, 1, 1}, {2, 2, 2}, {3, 3, 3}};
    const int species[3] = {0, 0, 0};
    const Real inverse_mass[1] = {1};
    int flag = 0;
    auto check = [&] {
        flag = 0;
        exec::for_each(exec::Host{}, 3,
                       gpu::PredictedDisplacementExceeds{x, v, f, species, inverse_mass, x_build, 0.005,
                                                         0.15 * 0.15, 1e10, &flag});
        return flag;
    };
    EXPECT_EQ(check(), 0);                     // at rest
    v[1] = {31, 0, 0};                         // next drift moves it 0.155 > 0.15
    EXPECT_EQ(check(), gpu::kRebuildNext);
    v[1] = {29, 0, 0};                         // 0.145
    EXPECT_EQ(check(), 0);
    f[2] = {0, nan, 0};                        // a NaN force
    EXPECT_EQ(check(), gpu::kRebuildNext | gpu::kNotFinite);
    f[2] = {0, 0, 0};
    x[0].z = std::numeric_limits<double>::infinity();
    EXPECT_EQ(check() & gpu::kNotFinite, gpu::kNotFinite);
    x[0].z = 1;
    f[0] = {0, 0, 1.1e5};                      // beyond the force bound of 1e5
    EXPECT_EQ(check() & gpu::kForceBound, gpu::kForceBound);
}

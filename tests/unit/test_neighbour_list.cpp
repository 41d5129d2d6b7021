// SPDX-License-Identifier: MIT
// The half Verlet list (cells + periodic ghosts) against a brute-force minimum-image search.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "decomposition/halo_exchange.hpp"
#include "decomposition/rank_grid.hpp"
#include "emergent/random.hpp"
#include "neighbour/cell_list.hpp"
#include "neighbour/neighbour_list.hpp"
#include "support/random_points.hpp"

using namespace emergent;

namespace {

/// Builds the list of 600 random points in a periodic box with cells of 1/subdivisions of the
/// list range (the cell search, or the general one) and checks it against brute force.
/// `reversed`: the owned particles in descending cell order, not the engine's ascending one
/// (the engine may also put some first: Simulation's halo overlap); the search is geometric,
/// so any order lists the same pairs.
/// With ranges by species (`by_species`): species i % 3 and each pair listed within its own
/// range of the table below plus the skin, never where the range is 0; `undescribed` gives
/// every 7th particle a species beyond the table, listed within the whole range.
/// `outside` (general search only): owned particles near the upper x face are moved up to 0.3
/// past it, as a rigid body's constituents stick out of their rank's domain, so their ghosts lie
/// inside the domain and cells hold owned particles and ghosts together.
void check_list_against_brute_force(int subdivisions, bool general, bool reversed = false,
                                    bool by_species = false, bool undescribed = false, bool outside = false) {
    SCOPED_TRACE("subdivisions " + std::to_string(subdivisions) + (general ? ", general" : "") +
                 (reversed ? ", reversed" : "") + (by_species ? ", by species" : "") +
                 (undescribed ? ", undescribed species" : "") + (outside ? ", owned outside" : ""));
    Box box;
    box.hi = {6.0, 7.5, 9.0};  // every edge > 2 (cutoff + skin): minimum image is unique
    decomp::RankGrid grid(MPI_COMM_SELF, box);
    ParticleStore store;
    const int n = 600;
    fixtures::add_uniform_particles(store, box.hi, n, 3);
    NeighbourList list(1.12, 0.38);
    const double rl = list.list_cutoff();
    // Short and long ranges, and pairs that never meet (a solvent among sites).
    const std::vector<double> range{0.5, 1.12, 0.0,  //
                                    1.12, 0.3, 0.8,  //
                                    0.0, 0.8, 1.12};
    if (by_species) {
        list.set_pair_ranges(range, 3);
        for (int i = 0; i < n; ++i) store.species[std::size_t(i)] = undescribed && i % 7 == 0 ? 3 : i % 3;
    }
    auto pair_range = [&](long a, long b) {  // by ids (= the particles' first indices)
        if (!by_species) return rl;
        const int sa = undescribed && a % 7 == 0 ? 3 : int(a % 3), sb = undescribed && b % 7 == 0 ? 3 : int(b % 3);
        if (sa > 2 || sb > 2) return rl;
        const double r = range[std::size_t(3 * sa + sb)];
        return r > 0 ? r + list.skin() : -1.0;
    };
    // Particles outside the domain widen the ghost shell by how far they stick out (as the
    // engine's ghost_width() does by the bodies' extent).
    const double shell = outside ? rl + 0.3 : rl;
    CellList cells;
    cells.setup(grid.lo(), grid.hi(), shell, rl, subdivisions);
    EXPECT_EQ(cells.reach().x, subdivisions);
    std::vector<std::uint32_t> order;
    cells.sort_order(store.position.data(), store.id.data(), store.n_owned(), order);
    if (reversed) std::reverse(order.begin(), order.end());
    store.permute_owned(order);
    int moved_out = 0;
    if (outside)
        for (std::size_t i = 0; i < store.n_owned(); ++i)
            if (store.position[i].x > box.hi.x - 0.3) {
                store.position[i].x += 0.3;
                moved_out += store.position[i].x >= box.hi.x ? 1 : 0;
            }
    if (outside) ASSERT_GT(moved_out, 5);
    decomp::HaloExchange halo;
    halo.build(store, grid, shell, kPosition | kId | kSpecies);
    cells.bin(store.position.data(), store.size());
    list.build(store, cells, general);

    // An owned–owned pair is listed once; an owned–ghost pair (here: across the periodic
    // boundary) is listed under each owned member, each taking half the pair's energy. So every
    // true pair must be covered exactly twice: 2 for an owned–owned entry, 1 per directed
    // owned–ghost entry.
    std::map<std::pair<long, long>, int> coverage;
    std::set<std::pair<long, long>> directed;
    for (std::size_t i = 0; i < store.n_owned(); ++i)
        for (auto k = list.offsets()[i]; k < list.offsets()[i + 1]; ++k) {
            const std::uint32_t j = list.neighbours()[k];
            const long a = store.id[i], b = store.id[j];
            EXPECT_TRUE(directed.insert({a, b}).second) << "entry listed twice: " << a << " " << b;
            coverage[{std::min(a, b), std::max(a, b)}] += j < store.n_owned() ? 2 : 1;
        }
    // Every pair in range is listed; the cell search (single precision, its range widened by
    // the rounding) may also list pairs within that widening, never further.
    std::set<std::pair<long, long>> expected, tolerated;
    const Vec3 len = box.length();
    const double widening = cells.binned_distance_error();
    ASSERT_LT(widening, rl * 1e-5);
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j) {
            Vec3 r = store.position[i] - store.position[j];
            for (int d = 0; d < 3; ++d) r[d] -= len[d] * std::round(r[d] / len[d]);
            const long a = store.id[i], b = store.id[j];
            const double reach = pair_range(a, b), widened = reach + widening;
            if (reach < 0) continue;
            if (dot(r, r) < reach * reach) expected.insert({std::min(a, b), std::max(a, b)});
            else if (dot(r, r) < widened * widened) tolerated.insert({std::min(a, b), std::max(a, b)});
        }
    for (const auto& [pair, count] : coverage)
        EXPECT_TRUE(expected.count(pair) || tolerated.count(pair))
            << "pair out of range listed: " << pair.first << " " << pair.second;
    for (const auto& pair : expected) {
        const auto it = coverage.find(pair);
        ASSERT_NE(it, coverage.end()) << "missed pair " << pair.first << " " << pair.second;
        EXPECT_EQ(it->second, 2) << pair.first << " " << pair.second;
    }
}

}  // namespace

TEST(NeighbourList, ListsExactlyThePairsWithinCutoffPlusSkinOnce) {
    for (int subdivisions : {1, 2, 3})
        for (bool general : {false, true}) check_list_against_brute_force(subdivisions, general);
    for (int subdivisions : {1, 2}) check_list_against_brute_force(subdivisions, false, true);
}

// Ranges by species pair (ForceTerm::pair_ranges): each pair within its own range plus the
// skin, none where its species never meet; a search from a species may stop at its longest
// range only when every species has its row, so undescribed ones are checked too.
TEST(NeighbourList, ListsThePairsWithinTheirSpeciesRange) {
    for (int subdivisions : {1, 2, 3})
        for (bool general : {false, true})
            for (bool undescribed : {false, true})
                check_list_against_brute_force(subdivisions, general, false, true, undescribed);
}

TEST(NeighbourList, GeneralSearchListsOwnedParticlesOutsideTheDomainAndGhostsInsideIt) {
    for (int subdivisions : {1, 2, 3})
        for (bool reversed : {false, true})
            for (bool by_species : {false, true})
                check_list_against_brute_force(subdivisions, true, reversed, by_species, false, true);
}

TEST(NeighbourList, RebuildIsRequestedOnlyBeyondHalfTheSkin) {
    Box box;
    box.hi = {5, 5, 5};
    decomp::RankGrid grid(MPI_COMM_SELF, box);
    ParticleStore store;
    store.add_owned({1, 1, 1}, {0, 0, 0}, 0, 0);
    store.add_owned({3, 3, 3}, {0, 0, 0}, 0, 1);
    NeighbourList list(1.0, 0.4);
    CellList cells;
    cells.setup(grid.lo(), grid.hi(), 1.4, 1.4);
    cells.bin(store.position.data(), store.size());
    list.build(store, cells);
    store.position[1].x += 0.19;
    EXPECT_FALSE(list.needs_rebuild(store, MPI_COMM_SELF));
    store.position[1].x += 0.02;
    EXPECT_TRUE(list.needs_rebuild(store, MPI_COMM_SELF));
}

// A point on a domain face belongs to the side the face rule says (lo inside, hi outside),
// whatever the rounding of its cell coordinate: a lattice start puts particles exactly there
// (an 80 x 80 x 40 layer on two ranks with skin 0.5 once put a ghost at y = 40 into an inner
// cell, and the build stopped).
TEST(CellList, PointsOnDomainFacesFallOnTheirSide) {
    int checked = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        const double lo = std::floor(200 * uniform_open(11, trial, 0) - 100) * 0.5;
        const double len = 4 + 120 * uniform_open(11, trial, 1);
        const double cell = 1.0 + 1.5 * uniform_open(11, trial, 2);
        const Vec3 lo3{lo, -0.5, 0.0}, hi3{lo + len, 40.0, 80.0};
        CellList cells;
        cells.setup(lo3, hi3, cell, cell);
        const Vec3 mid = 0.5 * (lo3 + hi3);
        for (int d = 0; d < 3; ++d) {
            const double inside[2] = {lo3[d], std::nextafter(hi3[d], lo3[d])};
            const double outside[2] = {hi3[d], std::nextafter(lo3[d], hi3[d] - 1e9)};
            for (int k = 0; k < 2; ++k) {
                Vec3 in = mid, out = mid;
                in[d] = inside[k];
                out[d] = outside[k];
                EXPECT_TRUE(cells.is_inner(cells.cell_of(in))) << "axis " << d << " at " << in[d];
                EXPECT_FALSE(cells.is_inner(cells.cell_of(out))) << "axis " << d << " at " << out[d];
                ++checked;
            }
        }
    }
    EXPECT_EQ(checked, 2000 * 6);
    // The case that failed in a run: domain y in [0, 40), list cutoff 1.122462 + 0.5.
    CellList cells;
    cells.setup({0, 0, -0.5}, {80, 40, 40.5}, 1.622462, 1.622462);
    EXPECT_FALSE(cells.is_inner(cells.cell_of({0.678, 40.0, 0.674})));
}

// A dilute gas in a huge domain (lj-fluid at density 1e-20: sides of 7e7) asked for 1e23 cells,
// past what an int counts, and the set-up crashed. The grid now holds at most 2^24 inner cells,
// wider than asked, and a pair within range is still found.
TEST(CellList, AHugeDomainGetsWiderCellsNotMoreThanMemoryHolds) {
    const double side = 7e7, range = 1.42;
    CellList cells;
    cells.setup({0, 0, 0}, {side, side, side}, range, range, 2);
    const CellIndex& g = cells.index();
    double inner = 1;
    for (int d = 0; d < 3; ++d) {
        inner *= g.end_inner[d] - g.first_inner[d];
        EXPECT_GE(1.0 / g.inverse_width[d], range / 2) << "axis " << d;
    }
    EXPECT_LE(inner, double(1 << 24));
    EXPECT_GT(inner, double(1 << 24) / 8);  // coarsened no more than needed
    // Two particles 1.0 apart, far out in the domain: one cell or neighbouring cells apart.
    ParticleStore store;
    store.add_owned({3.3e7, 1.1e7, 5.5e7}, {0, 0, 0}, 0, 0);
    store.add_owned({3.3e7 + 1.0, 1.1e7, 5.5e7}, {0, 0, 0}, 0, 1);
    cells.bin(store.position.data(), store.size());
    NeighbourList list(1.0, 0.42);
    list.build(store, cells);
    EXPECT_GE(list.n_pairs(), 1u);  // the only pair there is
}

TEST(CellList, BinningAfterASortEqualsBinningAnew) {
    // bin_after_sort takes the owned particles' cells from the sort that ordered them (and
    // partitioned them) and looks up only the ghosts; every cell must hold exactly what a
    // fresh bin() puts there.
    Box box;
    box.hi = {6.0, 7.5, 9.0};
    decomp::RankGrid grid(MPI_COMM_SELF, box);
    ParticleStore store;
    fixtures::add_uniform_particles(store, box.hi, 800, 5);
    const double rl = 1.5;
    CellList after_sort, fresh;
    after_sort.setup(grid.lo(), grid.hi(), rl, rl);
    fresh.setup(grid.lo(), grid.hi(), rl, rl);
    std::vector<std::uint32_t> order;
    after_sort.sort_order(store.position.data(), store.id.data(), store.n_owned(), order);
    // As the halo overlap orders them: the particles left of x = 2.7 first, each part in
    // cell order (a cell that straddles the line is split between the parts).
    const std::size_t n_front = after_sort.partition_sorted(
        order, [&](std::uint32_t i) { return store.position[i].x < 2.7; });
    for (std::size_t k = 0; k < order.size(); ++k)
        ASSERT_EQ(store.position[order[k]].x < 2.7, k < n_front) << "partitioned order at " << k;
    ASSERT_GT(n_front, 0u);
    ASSERT_LT(n_front, order.size());
    store.permute_owned(order);
    decomp::HaloExchange halo;
    halo.build(store, grid, rl, kPosition | kId);
    ASSERT_GT(store.size(), store.n_owned());  // ghosts to look up
    after_sort.bin_after_sort(store.position.data(), store.size());
    fresh.bin(store.position.data(), store.size());
    for (int c = 0; c < fresh.n_cells(); ++c) {
        ASSERT_EQ(after_sort.first(c), fresh.first(c)) << "cell " << c;
        for (std::uint32_t s = fresh.first(c); s < fresh.first(c + 1); ++s) {
            EXPECT_EQ(after_sort.members()[s], fresh.members()[s]);
        }
    }
    // Used once: a second binning looks every cell up again (positions may have moved).
    for (std::size_t i = 0; i < store.n_owned(); ++i) store.position[i].z = 0.5;
    after_sort.bin_after_sort(store.position.data(), store.size());
    fresh.bin(store.position.data(), store.size());
    for (int c = 0; c <= fresh.n_cells(); ++c) ASSERT_EQ(after_sort.first(c), fresh.first(c));
}


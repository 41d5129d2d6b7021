// SPDX-License-Identifier: MIT
// Choice of the rank grid and the thin-domain check.
#include <gtest/gtest.h>

#include "decomposition/load_balance.hpp"
#include "decomposition/rank_grid.hpp"
#include "emergent/error.hpp"

using emergent::Box;
using emergent::InputError;
using emergent::Vec3;
using emergent::decomp::RankGrid;

TEST(RankGrid, ChoosesTheGridWithLeastInterDomainSurface) {
    const bool all[3] = {true, true, true};
    const auto cube = RankGrid::choose_dims(8, {10, 10, 10}, all);
    EXPECT_EQ(cube.x * 100 + cube.y * 10 + cube.z, 222);
    const auto slab = RankGrid::choose_dims(4, {100, 10, 10}, all);  // long x: cut along x
    EXPECT_EQ(slab.x, 4);
    const bool z_only[3] = {false, false, true};
    const auto axial = RankGrid::choose_dims(6, {10, 10, 10}, z_only);
    EXPECT_EQ(axial.x * 100 + axial.y * 10 + axial.z, 116);
}

TEST(RankGrid, SubDomainsTileTheBoxAndThinDomainsAreRejected) {
    Box box;
    box.hi = {6, 7, 8};
    RankGrid grid(MPI_COMM_WORLD, box);
    double volume = grid.hi().x - grid.lo().x;
    volume *= (grid.hi().y - grid.lo().y) * (grid.hi().z - grid.lo().z);
    double total = 0;
    MPI_Allreduce(&volume, &total, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    EXPECT_NEAR(total, 6 * 7 * 8, 1e-9);
    EXPECT_NO_THROW(grid.require_width(1.0));
    EXPECT_THROW(grid.require_width(6.5), InputError);  // thicker than the whole x extent
}

using emergent::decomp::equal_share_planes;
using emergent::decomp::reachable_planes;

TEST(LoadBalance, EqualSharesOfACostProfile) {
    // Uniform cost: equal slabs.
    const std::vector<long long> flat(64, 10);
    const auto even = equal_share_planes(flat, 0, 8, 4);
    ASSERT_EQ(even.size(), 5u);
    for (int k = 0; k <= 4; ++k) EXPECT_DOUBLE_EQ(even[k], 2.0 * k);
    // A bed in the lowest quarter (cost 3 per bin) under a thin gas (1 per bin): bins 0..15
    // hold 48 and bins 16..63 hold 48, so half the work ends at the bed's top, 16.
    std::vector<long long> bed(64, 1);
    for (int b = 0; b < 16; ++b) bed[b] = 3;
    const auto two = equal_share_planes(bed, 0, 64, 2);
    EXPECT_DOUBLE_EQ(two[1], 16.0);
    // Within a bin the plane is placed linearly: all cost in bin 5 of 10 over [0, 10).
    std::vector<long long> spike(10, 0);
    spike[5] = 100;
    const auto s = equal_share_planes(spike, 0, 10, 4);
    EXPECT_DOUBLE_EQ(s[1], 5.25);
    EXPECT_DOUBLE_EQ(s[2], 5.5);
    EXPECT_DOUBLE_EQ(s[3], 5.75);
}

TEST(LoadBalance, PlanesMoveOnlyAsFarAsGhostsAndOneMigrationAllow) {
    const std::vector<double> current{0, 10, 20, 30, 40};
    // A target inside every limit is taken as it is.
    const std::vector<double> near{0, 11, 20.5, 29, 40};
    EXPECT_EQ(reachable_planes(current, near, 3.0, 1.0), near);
    // Squeezed: planes 1..3 towards 12, 13, 14 would make slabs 1 wide (min 3) and plane 3
    // leave [current[2] + 1, current[4] - 1] = [21, 39]: only part of the way is allowed.
    const std::vector<double> squeezed{0, 12, 13, 14, 40};
    const auto p = reachable_planes(current, squeezed, 3.0, 1.0);
    for (std::size_t k = 1; k < p.size(); ++k) EXPECT_GE(p[k] - p[k - 1], 3.0);
    for (std::size_t k = 1; k + 1 < p.size(); ++k) {
        EXPECT_GE(p[k], current[k - 1] + 1.0);
        EXPECT_LE(p[k], current[k + 1] - 1.0);
    }
    EXPECT_LT(p[3], 30.0);  // it did move towards the target
    EXPECT_GT(p[3], 14.0);
    // Nothing allowed (slabs already at the minimum width): the planes stay.
    const std::vector<double> tight{0, 3, 6, 9};
    EXPECT_EQ(reachable_planes(tight, {0, 1, 2, 9}, 3.0, 0.5), tight);
}

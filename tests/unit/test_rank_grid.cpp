// SPDX-License-Identifier: MIT
// Choice of the rank grid and the thin-domain check.
#include <gtest/gtest.h>

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

// SPDX-License-Identifier: MIT
// CycleAverage: samples grouped by whole cycles (a sample on a cycle's first instant belongs to
// it, the last cycle counts only once a later one has begun), each cycle weighing the same, the
// error from blocks of whole cycles, and its state surviving a checkpoint.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "emergent/block_error.hpp"
#include "emergent/kit/cycle_average.hpp"

using namespace emergent;

TEST(CycleAverage, WholeCyclesWeighTheSame) {
    CycleAverage a(2.5, 10.0);  // cycles of 2.5 from t = 10
    a.add(9.0, 100.0);          // before the start: ignored
    // Cycle 0: three samples (mean 2), cycle 1: one sample (4), cycle 2: still filling.
    for (double t : {10.0, 11.0, 12.0}) a.add(t, t - 9.0);
    a.add(10.0 + 2.5 * (1 + 1e-15), 4.0);  // rounding just past the boundary still cycle 1
    a.add(15.0, 1000.0);
    EXPECT_EQ(a.complete_cycles(), 2u);
    EXPECT_DOUBLE_EQ(a.mean(), (2.0 + 4.0) / 2);
    // A sample a hair before the boundary, by rounding, still opens the next cycle.
    CycleAverage b(0.1, 0.0);
    b.add(0.0, 1.0);
    b.add(0.3 - 1e-12, 5.0);  // 3 * 0.1 in floating point is 0.30000000000000004
    b.add(0.5, 0.0);
    EXPECT_EQ(b.complete_cycles(), 5u);
    EXPECT_EQ(b.cycle_means().size(), 2u);  // cycles 0 and 3 have samples; 1, 2, 4 are left out
    EXPECT_DOUBLE_EQ(b.mean(), 3.0);
}

TEST(CycleAverage, ErrorFromTheLongestBlocksLeavingSixteen) {
    std::mt19937_64 rng(5);
    std::normal_distribution<double> noise(0.0, 1.0);
    CycleAverage a(1.0, 0.0);
    std::vector<double> means;
    for (int k = 0; k < 100; ++k) {
        const double v = 0.3 + noise(rng);
        a.add(k + 0.5, v);
        means.push_back(v);
    }
    a.add(100.5, 0.0);  // closes cycle 99
    // 100 cycles: blocks of 4 leave 25 >= 16, blocks of 8 only 12.
    const double se = a.standard_error();
    EXPECT_EQ(a.block_cycles(), 4u);
    // Against the blocking written out here.
    std::vector<double> blocks(25, 0.0);
    for (int b = 0; b < 25; ++b) {
        for (int k = 0; k < 4; ++k) blocks[b] += means[4 * b + k] / 4;
    }
    double m = 0, var = 0;
    for (double x : blocks) m += x / 25;
    for (double x : blocks) var += (x - m) * (x - m) / 24;
    EXPECT_NEAR(se, std::sqrt(var / 25), 1e-12);
    // Independent unit-variance cycle means: the error is about 1/sqrt(100).
    EXPECT_NEAR(se, 0.1, 0.04);
    EXPECT_TRUE(std::isnan(CycleAverage(1.0).standard_error()));
}

TEST(CycleAverage, StateSurvivesACheckpoint) {
    CycleAverage a(0.5, 1.0);
    for (int k = 0; k < 40; ++k) a.add(1.0 + 0.1 * k, std::sin(0.7 * k));
    CycleAverage b;
    ASSERT_TRUE(b.restore(a.state()));
    EXPECT_EQ(b.mean(), a.mean());
    EXPECT_EQ(b.complete_cycles(), a.complete_cycles());
    b.add(5.2, 1.0), a.add(5.2, 1.0);
    EXPECT_EQ(b.mean(), a.mean());
    EXPECT_FALSE(b.restore({1.0, 2.0, 3.0}));  // odd length: malformed, refused
    EXPECT_FALSE(b.restore({0.0, 2.0}));        // no period
}

TEST(BlockError, NeedsTwoWholeBlocks) {
    const std::vector<double> x{1, 2, 3, 4, 5, 6};
    EXPECT_TRUE(std::isnan(block_standard_error(x, 3, 1)));
    EXPECT_TRUE(std::isnan(block_standard_error(x, 4, 2)));
    // Blocks {1,2,3} and {4,5,6}: means 2 and 5, sd 2.12..., error 1.5.
    EXPECT_DOUBLE_EQ(block_standard_error(x, 3, 2), 1.5);
}

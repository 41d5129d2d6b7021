// SPDX-License-Identifier: MIT
// Segregation measures against cases whose answer is known: complete segregation, and random
// mixtures (the index's random-mixture spread against dealing the labels at random).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "emergent/kit/segregation.hpp"

using namespace emergent;

TEST(SplitSegregation, CompleteSegregationGivesOneAndRandomLabelsMatchTheComputedSpread) {
    std::vector<double> x(1000);
    std::vector<char> m(1000);
    for (int i = 0; i < 1000; ++i) x[i] = i, m[i] = i < 300;  // marked all on the inner side
    const SplitSegregation full = split_segregation(x, m, MPI_COMM_SELF);
    EXPECT_NEAR(full.inner_fraction, 0.6, 1e-12);
    EXPECT_NEAR(full.outer_fraction, 0.0, 1e-12);
    EXPECT_NEAR(full.index, 0.6, 1e-12);

    // Deal 300 marks at random over the same positions many times: the index's mean is 0 and
    // its standard deviation the computed random_sd. 4000 trials: the mean is known to
    // +-3 sd/sqrt(4000) = 0.05 sd and the sd to about +-3 x 1.1 % (chi distribution).
    std::mt19937_64 rng(3);
    double sum = 0, sum2 = 0, sd = 0;
    const int trials = 4000;
    for (int k = 0; k < trials; ++k) {
        std::shuffle(m.begin(), m.end(), rng);
        const SplitSegregation s = split_segregation(x, m, MPI_COMM_SELF);
        sum += s.index, sum2 += s.index * s.index, sd = s.random_sd;
    }
    const double mean = sum / trials, spread = std::sqrt(sum2 / trials - mean * mean);
    EXPECT_LT(std::fabs(mean), 0.05 * sd);
    EXPECT_NEAR(spread / sd, 1.0, 0.035);
}

TEST(BandCensus, CountsBandsAndRatesContrastAgainstARandomMixture) {
    // Four bands along 40 slices of 200 members each: marked fraction 0.9 / 0.1 alternating.
    MixtureBins bins;
    bins.lo = 0, bins.hi = 40;
    for (int k = 0; k < 40; ++k) {
        bins.count.push_back(200);
        bins.marked.push_back((k / 10) % 2 ? 20 : 180);
    }
    const BandCensus banded = band_census(bins);
    EXPECT_EQ(banded.bands, 4);
    ASSERT_EQ(banded.boundaries.size(), 3u);
    EXPECT_NEAR(banded.boundaries[0], 10, 1.0);
    EXPECT_GT(banded.contrast, 10);

    // A random mixture: binomial counts; contrast about 1, one band.
    std::mt19937_64 rng(5);
    std::binomial_distribution<int> draw(200, 0.33);
    double contrast = 0;
    int extra_bands = 0;
    for (int trial = 0; trial < 200; ++trial) {
        for (int k = 0; k < 40; ++k) bins.marked[k] = draw(rng);
        const BandCensus mixed = band_census(bins);
        contrast += mixed.contrast / 200;
        extra_bands += mixed.bands - 1;
    }
    // Mean of sqrt(chi^2_40 / 40) ~ 0.99 (the overall fraction is estimated, -1/40): +-0.05.
    EXPECT_NEAR(contrast, 1.0, 0.05);
    // Changes between extremes beyond 3 sd on both sides are rare in pure noise.
    EXPECT_LT(extra_bands, 20);
}

TEST(MixtureBins, CountsMembersInRangeOnly) {
    const std::vector<double> x{-0.5, 0.1, 0.2, 1.5, 2.9, 3.0};
    const std::vector<char> m{1, 1, 0, 1, 0, 1};
    const MixtureBins b = mixture_bins(x, m, 0, 3, 3, MPI_COMM_SELF);
    EXPECT_EQ(b.count, (std::vector<double>{2, 1, 1}));
    EXPECT_EQ(b.marked, (std::vector<double>{1, 1, 0}));
    const auto f = b.fraction();
    EXPECT_DOUBLE_EQ(f[0], 0.5);
}

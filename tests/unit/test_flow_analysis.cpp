// SPDX-License-Identifier: MIT
// The vortex census, the dominant axial mode and the measured noise level on profiles whose
// answers are known by construction.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "emergent/kit/flow_analysis.hpp"
#include "emergent/random.hpp"

using namespace emergent;

namespace {
constexpr double kPi = 3.14159265358979323846;
}

TEST(RollCensus, FindsTheZeroCrossingsOfAnAlternatingFlow) {
    // v = sin(2 pi z / 25) on 100 cells of width 1 (centres at k + 0.5): zero crossings at
    // z = 12.5, 25, ..., 87.5 (7 of them inside), each a vortex centre between an outflow and
    // an inflow.
    const int n = 100;
    std::vector<double> v(n), noise(n, 0.01);
    for (int k = 0; k < n; ++k) v[k] = std::sin(2 * kPi * (k + 0.5) / 25);
    const RollCensus census = count_rolls(v, noise, 0.5, 1.0);
    ASSERT_EQ(census.count, 7);
    // Linear interpolation between cell centres of a sine: error below (1 cell)^2 curvature.
    for (int j = 0; j < 7; ++j) EXPECT_NEAR(census.centres[j], 12.5 * (j + 1), 0.02);
    // The same flow buried in noise 10x its amplitude holds no significant cell: no vortices.
    std::vector<double> loud(n, 10.0);
    EXPECT_EQ(count_rolls(v, loud, 0.5, 1.0).count, 0);
}

TEST(DominantMode, FindsTheWaveOfAPeriodicAndOfABoundedProfile) {
    const int n = 64;
    const double length = 128;
    std::vector<double> periodic(n), bounded(n);
    for (int k = 0; k < n; ++k) {
        const double z = (k + 0.5) * length / n;
        periodic[k] = 0.3 * std::sin(2 * kPi * 4 * z / length) + 0.1;  // mode 4, offset ignored
        bounded[k] = 0.5 * std::cos(kPi * 5 * z / length);              // cosine mode 5
    }
    const DominantMode p = dominant_mode(periodic, length, true);
    EXPECT_EQ(p.index, 4);
    EXPECT_DOUBLE_EQ(p.wavelength, length / 4);
    EXPECT_NEAR(p.amplitude, 0.3, 1e-9);
    const DominantMode b = dominant_mode(bounded, length, false);
    EXPECT_EQ(b.index, 5);
    EXPECT_DOUBLE_EQ(b.wavelength, 2 * length / 5);
    EXPECT_NEAR(b.amplitude, 0.5, 1e-9);
}

TEST(NoiseFactor, MeasuresHowMuchTheModelUnderestimatesTheNoise) {
    // Two frames of a steady profile plus independent noise of sd 3x what the model says.
    const int n = 4000;
    std::vector<double> a(n), b(n), model(n, 0.02);
    for (int k = 0; k < n; ++k) {
        const double steady = 0.4 * std::sin(k * 0.01);
        a[k] = steady + 0.06 * gaussian(5, k, 0);
        b[k] = steady + 0.06 * gaussian(5, k, 1);
    }
    // The estimate's relative sd is 1/sqrt(2n) = 1.1 %: 3 +- 0.1 is a 3-sigma band.
    EXPECT_NEAR(noise_factor_from_frames(a, model, b, model), 3.0, 0.1);
    // Cells with a non-finite value are skipped, not propagated.
    a[7] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_NEAR(noise_factor_from_frames(a, model, b, model), 3.0, 0.1);
    // A profile that did not change at all: never below the model.
    EXPECT_DOUBLE_EQ(noise_factor_from_frames(b, model, b, model), 1.0);
    EXPECT_DOUBLE_EQ(noise_factor_from_frames({}, {}, {}, {}), 1.0);
}

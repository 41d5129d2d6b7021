// SPDX-License-Identifier: MIT
// PlanarNoise: the seed field for an instability must hold the rms it is given, have no power
// beyond its shortest wavelength and the same power in every mode it admits (no wavelength
// favoured), and be periodic, deterministic and seed-dependent.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <vector>

#include "emergent/kit/planar_noise.hpp"

using namespace emergent;

namespace {

constexpr double kTwoPi = 6.283185307179586;

/// The field on an n x n grid over the plane.
std::vector<double> sample(const PlanarNoise& f, double lx, double ly, int n) {
    std::vector<double> v(static_cast<std::size_t>(n) * n);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) v[j * n + i] = f(lx * i / n, ly * j / n);
    return v;
}

/// |Fourier coefficient|^2 of the sampled field at integer wave numbers (nx, ny).
double power(const std::vector<double>& v, int n, int nx, int ny) {
    std::complex<double> c = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            c += v[j * n + i] * std::polar(1.0, -kTwoPi * (double(nx) * i + double(ny) * j) / n);
    return std::norm(c / double(n * n));
}

}  // namespace

TEST(PlanarNoise, ModeCountIsTheLatticePointsInsideTheCutOffDisc) {
    // A square plane of side 8 lambda_min: the wave vectors are the integer points of a disc of
    // radius 8 (Gauss's circle problem: 197 of them), less the origin, one of each +-k pair.
    EXPECT_EQ(PlanarNoise(160, 160, 20, 0.1, 1).modes(), (197u - 1) / 2);
    // Radius 3: 29 points.
    EXPECT_EQ(PlanarNoise(60, 60, 20, 0.1, 1).modes(), (29u - 1) / 2);
}

TEST(PlanarNoise, HoldsItsRmsAndZeroMeanOverThePlane) {
    // On a uniform grid finer than the shortest wavelength the discrete sums of the cosines
    // are exact, so the rms is the requested one to round-off.
    for (const double rms : {0.05, 0.2}) {
        const PlanarNoise f(160, 120, 20, rms, 7);
        const auto v = sample(f, 160, 120, 64);
        double sum = 0, sq = 0;
        for (double x : v) sum += x, sq += x * x;
        EXPECT_NEAR(sum / v.size(), 0.0, 1e-12);
        EXPECT_NEAR(std::sqrt(sq / v.size()), rms, 1e-9 * rms);
    }
}

TEST(PlanarNoise, EqualPowerInEveryAdmittedModeAndNoneBeyondTheCutOff) {
    const double l = 100, lambda = 25;  // wave numbers |n| <= 4
    const int n = 32;
    const PlanarNoise f(l, l, lambda, 0.1, 3);
    const auto v = sample(f, l, l, n);
    // A cosine of amplitude a has power (a / 2)^2 at k and at -k; a^2 = 2 rms^2 / modes.
    const double each = 0.1 * 0.1 / (2.0 * f.modes());
    int admitted = 0;
    for (int ny = -8; ny <= 8; ++ny)
        for (int nx = -8; nx <= 8; ++nx) {
            if (nx == 0 && ny == 0) continue;
            const double p = power(v, n, nx, ny);
            if (nx * nx + ny * ny <= 16) {
                ++admitted;
                EXPECT_NEAR(p, each, 1e-9 * each) << nx << " " << ny;
            } else {
                EXPECT_LT(p, 1e-12 * each) << nx << " " << ny;
            }
        }
    EXPECT_EQ(admitted, static_cast<int>(2 * f.modes()));
}

TEST(PlanarNoise, PeriodicDeterministicAndSeedDependent) {
    const PlanarNoise a(80, 50, 10, 0.1, 11), same(80, 50, 10, 0.1, 11), other(80, 50, 10, 0.1, 12);
    double differ = 0;
    for (int k = 0; k < 50; ++k) {
        const double x = 1.7 * k, y = 0.9 * k + 0.3;
        EXPECT_NEAR(a(x + 80, y), a(x, y), 1e-12);
        EXPECT_NEAR(a(x, y - 50), a(x, y), 1e-12);
        EXPECT_EQ(a(x, y), same(x, y));
        differ += std::abs(a(x, y) - other(x, y));
    }
    EXPECT_GT(differ / 50, 0.01);
    EXPECT_LE(std::abs(a(3, 4)), a.bound());
}

TEST(PlanarNoise, RefusesAPlaneWithNoModeLongEnough) {
    EXPECT_THROW(PlanarNoise(10, 10, 20, 0.1, 1), std::exception);
    EXPECT_EQ(PlanarNoise(10, 10, 20, 0, 1).modes(), 0u);
}

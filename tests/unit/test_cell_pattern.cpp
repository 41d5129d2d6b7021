// SPDX-License-Identifier: MIT
// Cell-pattern analysis against patterns whose answers are known exactly (lattices, a single
// cell, synthetic hexagonal fields) or from stochastic geometry (Poisson-Voronoi tessellation).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "emergent/kit/cell_pattern.hpp"

using namespace emergent;

namespace {

constexpr double kPi = 3.141592653589793;

/// Triangular lattice of spacing a, n columns and m rows (m even, so it tiles the rectangle
/// n a x m a sqrt(3)/2 periodically), shifted by `offset`.
std::vector<Point2> hexagonal_lattice(double a, int n, int m, Point2 offset) {
    std::vector<Point2> p;
    for (int j = 0; j < m; ++j)
        for (int i = 0; i < n; ++i)
            p.push_back({offset[0] + (i + 0.5 * (j % 2)) * a, offset[1] + j * a * std::sqrt(3.0) / 2});
    return p;
}

/// -sum of the three plane waves whose crests meet on that lattice: minima exactly on it.
PeriodicField2D hexagonal_field(double a, int n, int m, int cells_x, int cells_y, Point2 offset) {
    PeriodicField2D f{cells_x, cells_y, n * a, m * a * std::sqrt(3.0) / 2, {}};
    const double q = 2 * kPi / a;
    for (int j = 0; j < cells_y; ++j)
        for (int i = 0; i < cells_x; ++i) {
            const double x = (i + 0.5) * f.lx / cells_x - offset[0];
            const double y = (j + 0.5) * f.ly / cells_y - offset[1];
            const double s = 1 / std::sqrt(3.0);
            f.value.push_back(-(std::cos(q * (x - s * y)) + std::cos(q * 2 * s * y) + std::cos(q * (x + s * y))));
        }
    return f;
}

}  // namespace

TEST(PeriodicVoronoi, HexagonalLatticeGivesRegularHexagons) {
    // Every polygon of a triangular lattice is a regular hexagon whose inradius is half the
    // spacing; only rounding separates the computed values from the exact ones.
    const double a = 7.3;
    const auto points = hexagonal_lattice(a, 8, 6, {0.31, 1.7});
    const VoronoiPattern v = periodic_voronoi(points, 8 * a, 6 * a * std::sqrt(3.0) / 2);
    ASSERT_EQ(v.cells, 48);
    EXPECT_EQ(v.six_sided_fraction, 1.0);
    EXPECT_EQ(v.edge_histogram[6], 48);
    EXPECT_NEAR(v.mean_inradius, a / 2, 1e-9 * a);
    EXPECT_NEAR(v.mean_radial_range, 0.0, 1e-9 * a);
    EXPECT_NEAR(v.wavelength(), a, 1e-9 * a);
}

TEST(PeriodicVoronoi, SquareLatticeMergesCocircularVertices) {
    // Four centres on every circle: the triangulation's diagonals have zero-length duals, which
    // must not count as edges. Square polygons, inradius a/2.
    std::vector<Point2> points;
    const double a = 2.5;
    for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 7; ++i) points.push_back({(i + 0.5) * a, (j + 0.5) * a});
    const VoronoiPattern v = periodic_voronoi(points, 7 * a, 5 * a);
    EXPECT_EQ(v.edge_histogram[4], 35);
    EXPECT_NEAR(v.mean_inradius, a / 2, 1e-9 * a);
    EXPECT_NEAR(v.mean_edges, 4.0, 1e-12);
}

TEST(PeriodicVoronoi, OnePointOwnsTheWholeRectangle) {
    // Its polygon is the rectangle itself: edges at lx/2 and ly/2.
    const VoronoiPattern v = periodic_voronoi({{3.0, 1.0}}, 10.0, 4.0);
    ASSERT_EQ(v.cells, 1);
    EXPECT_EQ(v.edges[0], 4);
    EXPECT_NEAR(v.inradius[0], (5.0 + 2.0) / 2, 1e-12);
    EXPECT_NEAR(v.radial_range[0], 3.0, 1e-12);
}

TEST(PeriodicVoronoi, PoissonPointsMatchStochasticGeometry) {
    // On a torus every simple tessellation has exactly 6 edges per polygon on average (Euler:
    // V - E + F = 0 with three edges at each vertex). For Poisson points the fraction of
    // six-sided polygons is 0.29468 (Hinde & Miles, J. Stat. Comput. Simul. 10, 205 (1980));
    // with 4000 polygons its sampling error is ~sqrt(0.29 x 0.71 / 4000) = 0.0072: 4 of those.
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> u(0, 1);
    const double lx = 60, ly = 100;  // not square
    std::vector<Point2> points(4000);
    for (auto& p : points) p = {lx * u(rng), ly * u(rng)};
    const VoronoiPattern v = periodic_voronoi(points, lx, ly);
    EXPECT_NEAR(v.mean_edges, 6.0, 1e-12);
    EXPECT_NEAR(v.six_sided_fraction, 0.29468, 4 * 0.0072);
}

namespace {
/// The minima of hexagonal_field(a, 4, 4, 48, 42, offset) against its lattice: all 16 found,
/// each within 5 % of a grid cell of a lattice point, and their polygons regular hexagons.
void check_minima_on_lattice(const Point2& offset) {
    const double a = 12.0;
    const PeriodicField2D f = hexagonal_field(a, 4, 4, 48, 42, offset);
    const auto minima = local_minima(f);
    ASSERT_EQ(minima.size(), 16u);
    const auto lattice = hexagonal_lattice(a, 4, 4, offset);
    const double dx = f.lx / f.nx;
    for (const Point2& p : minima) {
        EXPECT_TRUE(p[0] >= 0 && p[0] < f.lx && p[1] >= 0 && p[1] < f.ly);  // folded into the box
        double best = 1e300;
        for (const Point2& q : lattice) {
            double ex = std::remainder(p[0] - q[0], f.lx), ey = std::remainder(p[1] - q[1], f.ly);
            best = std::min(best, std::hypot(ex, ey));
        }
        EXPECT_LT(best, 0.05 * dx);
    }
    const VoronoiPattern v = periodic_voronoi(minima, f.lx, f.ly);
    EXPECT_EQ(v.six_sided_fraction, 1.0);
    EXPECT_NEAR(v.wavelength(), a, 0.02 * a);
}
}  // namespace

TEST(CellCentres, MinimaOfAHexagonalFieldLieOnItsLattice) {
    // The field's minima sit exactly on a lattice that is offset from the grid's cell centres;
    // the parabola through neighbouring cells places them to a small fraction of a cell.
    check_minima_on_lattice({3.1, 2.2});
}

TEST(CellCentres, MinimaAcrossThePeriodicEdgesAreFoundOnce) {
    // Lattice points a hair inside the left edge and a hair below the top edge (which wraps
    // onto the bottom): each minimum's neighbours lie across an edge, and its parabola fit
    // reaches over it; none may be lost or found twice.
    const double dx = 48.0 / 48, dy = 4 * 12.0 * std::sqrt(3.0) / 2 / 42;
    check_minima_on_lattice({0.05 * dx, 4 * 12.0 * std::sqrt(3.0) / 2 - 0.1 * dy});
}

TEST(CellCentres, SmoothingDampsEachWaveByItsGaussianFactor) {
    // A single Fourier mode is an eigenfunction of the periodic Gaussian smoothing, with factor
    // exp(-k^2 w^2 / 2); the FFT makes that exact to rounding.
    PeriodicField2D f{32, 16, 40.0, 20.0, {}};
    const double k = 2 * kPi * 3 / f.lx, w = 1.7;
    for (int j = 0; j < f.ny; ++j)
        for (int i = 0; i < f.nx; ++i) f.value.push_back(5 + std::cos(k * (i + 0.5) * f.lx / f.nx));
    const PeriodicField2D s = smooth_periodic(f, w);
    const double factor = std::exp(-0.5 * k * k * w * w);
    for (std::size_t c = 0; c < f.value.size(); ++c)
        EXPECT_NEAR(s.value[c], 5 + factor * (f.value[c] - 5), 1e-12);
}

TEST(PatternSpectrum, FindsTheWavelengthOfRollsAndHexagons) {
    // Rolls of wavelength lx/5 along x; hexagons of spacing a, made of three waves of
    // wavelength (sqrt 3 / 2) a. Both are whole modes of the box, so the spectrum is exact.
    PeriodicField2D rolls{64, 48, 80.0, 60.0, {}};
    for (int j = 0; j < rolls.ny; ++j)
        for (int i = 0; i < rolls.nx; ++i)
            rolls.value.push_back(std::sin(2 * kPi * 5 * (i + 0.5) / rolls.nx));
    EXPECT_NEAR(pattern_spectrum(rolls).dominant_wavelength, 16.0, 1e-9);

    const double a = 12.0;
    const PeriodicField2D hex = hexagonal_field(a, 4, 4, 48, 42, {1.0, 2.0});
    EXPECT_NEAR(pattern_spectrum(hex).dominant_wavelength, std::sqrt(3.0) / 2 * a, 1e-9);
}

TEST(PeriodicVoronoi, NoPointsGiveNoPolygonsAndNoMeans) {
    // A slice without minima has no cells; its means are undefined (NaN), not zero, so a plot
    // of the wavelength against time shows a gap, not a false zero.
    const VoronoiPattern v = periodic_voronoi({}, 10, 10);
    EXPECT_EQ(v.cells, 0);
    EXPECT_TRUE(std::isnan(v.mean_edges));
    EXPECT_TRUE(std::isnan(v.six_sided_fraction));
    EXPECT_TRUE(std::isnan(v.mean_inradius));
    EXPECT_TRUE(std::isnan(v.wavelength()));
}

TEST(PatternSpectrum, AFlatFieldHasNoDominantWavelength) {
    PeriodicField2D f{16, 8, 20.0, 10.0, std::vector<double>(16 * 8, 3.5)};
    EXPECT_TRUE(std::isnan(pattern_spectrum(f).dominant_wavelength));
}

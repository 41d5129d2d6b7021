// SPDX-License-Identifier: MIT
// Analysis of cellular patterns in a periodic plane (Rayleigh-Benard convection cells): cell
// centres as local extremes of a field, periodic Voronoi polygons of the centres, and the
// field's power spectrum.
#pragma once

#include <array>
#include <cmath>
#include <vector>

namespace emergent {

/// A scalar field on an nx x ny grid of cells covering the periodic rectangle [0, lx) x
/// [0, ly); value[i + nx j] belongs to the cell centred at ((i + 1/2) lx / nx, (j + 1/2) ly / ny).
struct PeriodicField2D {
    int nx = 0, ny = 0;
    double lx = 0, ly = 0;
    std::vector<double> value;
};

using Point2 = std::array<double, 2>;

/// The field convolved with a periodic Gaussian of standard deviation `width` (length units),
/// by FFT; width 0 returns it unchanged.
PeriodicField2D smooth_periodic(const PeriodicField2D& field, double width);

/// Local minima: cells lower than their eight neighbours (periodic; of two equal values the
/// one with the lower index counts as lower), each placed at the vertex of the parabola through
/// it and its two neighbours along x and along y.
std::vector<Point2> local_minima(const PeriodicField2D& field);

/// Voronoi polygons of points in the periodic rectangle [0, lx) x [0, ly).
///
/// Each polygon is measured from its own centre: its edges (only those of non-zero length: a
/// vertex shared by four or more centres is one vertex), and the distance from the centre to
/// each edge's line, which is half the distance to the neighbour across that edge. The
/// polygon's inradius is the mean of those distances, its radial range their max - min (zero
/// for a regular polygon).
struct VoronoiPattern {
    int cells = 0;
    std::vector<int> edges;           ///< per polygon, in the order of the points
    std::vector<double> inradius;     ///< per polygon
    std::vector<double> radial_range; ///< per polygon
    // The means are NaN without any polygon (no point), so that no false zero is plotted.
    double mean_edges = NAN;          ///< exactly 6 on a torus (Euler) for a simple tessellation
    double six_sided_fraction = NAN;
    double mean_inradius = NAN;
    double mean_radial_range = NAN;
    double radial_range_spread = NAN; ///< standard deviation of radial_range over polygons
    /// Paper's wavelength of the cell array: 2 x mean inradius (= centre spacing of hexagons).
    double wavelength() const { return 2 * mean_inradius; }
    /// Polygons with k edges, k = 0 .. 12 (13 and more in the last entry).
    std::array<int, 14> edge_histogram{};
};

/// Computed from the Delaunay triangulation (CGAL, exact predicates) of the points and their
/// periodic images, which works for any rectangle and any point set of at least one point.
VoronoiPattern periodic_voronoi(const std::vector<Point2>& points, double lx, double ly);

/// Power spectrum of the field's deviation from its mean, binned in shells of |k| of width
/// 2 pi / max(lx, ly). The dominant wavelength is 2 pi / <|k|> over the strongest shell, the
/// mean weighted by power. For hexagonal cells of centre spacing a it is (sqrt 3 / 2) a (the
/// three waves that make the hexagons); for rolls of wavelength lambda it is lambda.
struct PatternSpectrum {
    double shell_width = 0;            ///< in k
    std::vector<double> shell_power;   ///< sum of |F_k|^2 / (nx ny)^2 over each shell; shell 0 unused
    int dominant_shell = 0;
    double dominant_wavelength = NAN;  ///< NaN for a field without structure (flat)
};
PatternSpectrum pattern_spectrum(const PeriodicField2D& field);

}  // namespace emergent

// SPDX-License-Identifier: MIT
// Initial placement of a fluid on a lattice filling a region of any shape.
#pragma once

#include <cstdint>
#include <cmath>
#include <functional>
#include <vector>

#include "emergent/vec3.hpp"

namespace emergent {

class Simulation;

/// Adds particles at rest (species 0, diameter 1) on a rectangular lattice of `spacing` per
/// axis, at the points lo + spacing * (i + 1/2, j + 1/2, k + 1/2) inside [lo, hi) for which
/// `inside` is true. Ids run from `first_id` in lattice order, the same on every rank. Returns the number
/// of points kept (all ranks together).
std::int64_t fill_cubic_lattice(Simulation& sim, const Vec3& lo, const Vec3& hi, const Vec3& spacing,
                                const std::function<bool(const Vec3&)>& inside,
                                std::int64_t first_id = 0);

/// Number of points fill_cubic_lattice would place (no particles are added).
std::int64_t count_cubic_lattice(const Vec3& lo, const Vec3& hi, const Vec3& spacing,
                                 const std::function<bool(const Vec3&)>& inside);

/// Adds `target` particles, or within 0.1 % of it, on a rectangular lattice filling the
/// region: the spacing is adjusted until the count matches (the number density of a region
/// whose walls cut the lattice is then what was asked for, not that of the infinite
/// lattice). `periodic[d]` keeps a whole number of cells along axis d. Returns the count.
std::int64_t fill_lattice_with_count(Simulation& sim, const Vec3& lo, const Vec3& hi,
                                     std::int64_t target, const bool periodic[3],
                                     const std::function<bool(const Vec3&)>& inside);

/// The spacing (per axis) at which the lattice of fill_cubic_lattice has `target` points, or
/// within 0.1 % of it, inside the region (see fill_lattice_with_count).
Vec3 spacing_for_count(const Vec3& lo, const Vec3& hi, std::int64_t target, const bool periodic[3],
                       const std::function<bool(const Vec3&)>& inside);

/// The lattice points fill_cubic_lattice would use, in its order (the same on every rank).
std::vector<Vec3> cubic_lattice_points(const Vec3& lo, const Vec3& hi, const Vec3& spacing,
                                       const std::function<bool(const Vec3&)>& inside);

/// Fills the layer of wall_bounded_layer(lx, ly, height) with round(density lx ly height)
/// particles (fill_lattice_with_count; whole lattice planes across x and y). Returns the count.
std::int64_t fill_wall_bounded_layer(Simulation& sim, double lx, double ly, double height,
                                     double density);

/// Centres for spheres of the given diameters, placed one after another at uniformly random
/// points of [lo, hi) where `inside(x, d)` holds, each where it overlaps none placed before
/// (centres at least range (d_i + d_j) / 2 apart): random sequential addition, which reaches
/// volume fractions near 0.3 quickly (a loose start for a granular layer that then settles a
/// short way, rather than a sparse lattice that falls far). The same for a seed on every rank.
/// Throws InputError when a sphere finds no place in `tries` attempts (the region is too full).
std::vector<Vec3> random_sequential_packing(const Vec3& lo, const Vec3& hi,
                                            const std::vector<double>& diameters, double range,
                                            std::uint64_t seed,
                                            const std::function<bool(const Vec3&, double)>& inside,
                                            int tries = 20000);

/// Lattice spacing for number density `density` on a simple cubic lattice.
inline double cubic_spacing(double density) { return 1.0 / std::cbrt(density); }

/// The spacing nearest `spacing` that fits a whole number of cells into `length` (for
/// periodic directions, where the lattice must tile the box).
inline double tiling_spacing(double length, double spacing) {
    const double n = std::round(length / spacing);
    return length / (n < 1 ? 1 : n);
}

}  // namespace emergent

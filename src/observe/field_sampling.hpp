// SPDX-License-Identifier: MIT
// One sample of the coarse-grained fields: per-cell sums over the owned particles (count, mass,
// momentum along the grid's axes, m v^2), positions folded into the box along its periodic
// axes first. The host scatters in index order into zeroed sums; the back end sorts the
// particles by cell (stably) and sums each cell's members in index order: the same additions,
// so both give the same bits.
#pragma once

#include <cstddef>
#include <cstdint>

#include "emergent/box.hpp"
#include "emergent/field_grid.hpp"

namespace emergent::observe {

constexpr int kFieldSums = 6;  ///< per cell: count, mass, momentum (3), m v^2

/// Adds one particle (folded position x, velocity v, mass m) to its cell's sums s.
EMERGENT_HD inline void add_to_cell(const FieldGeometry& grid, const Vec3& x, const Vec3& velocity, double m,
                                    double* s) {
    const Vec3 v = grid.components(x, velocity);
    s[0] += 1;
    s[1] += m;
    s[2] += m * v.x;
    s[3] += m * v.y;
    s[4] += m * v.z;
    s[5] += m * dot(v, v);
}

/// The host's sample: particles [0, n) scattered in index order into `sums` (zeroed first).
inline void scatter_field_sums(const FieldGeometry& grid, const Box& box, std::size_t n, const Vec3* x,
                               const Vec3* v, const int* species, const double* mass, double* sums) {
    for (int k = 0; k < grid.n_cells() * kFieldSums; ++k) sums[k] = 0;
    for (std::size_t i = 0; i < n; ++i) {
        // Between list builds owned particles may sit just past a periodic face; a hair below
        // lo must land at lo, not round up to hi (outside every cell).
        const Vec3 p = box.primary_image(x[i]);
        const int c = grid.cell_of(p);
        if (c >= 0) add_to_cell(grid, p, v[i], mass[species[i]], sums + static_cast<std::size_t>(c) * kFieldSums);
    }
}

/// The back end's sample, first pass: key[i] = particle i's cell (n_cells outside the grid,
/// so those sort last), value[i] = i.
struct FieldCellKey {
    FieldGeometry grid;
    Box box;
    const Vec3* x;
    std::uint32_t* key;
    std::uint32_t* value;
    EMERGENT_HD void operator()(std::size_t i) const {
        const int c = grid.cell_of(box.primary_image(x[i]));
        key[i] = static_cast<std::uint32_t>(c < 0 ? grid.n_cells() : c);
        value[i] = static_cast<std::uint32_t>(i);
    }
};

/// Second pass, per cell c: the sums over its members member[start[c] .. start[c + 1]) in
/// index order (the keys sorted stably), into out[c * kFieldSums ...].
struct FieldCellSums {
    FieldGeometry grid;
    Box box;
    const Vec3* x;
    const Vec3* v;
    const int* species;
    const double* mass;
    const std::uint32_t* start;
    const std::uint32_t* member;
    double* out;
    EMERGENT_HD void operator()(std::size_t c) const {
        double s[kFieldSums] = {0, 0, 0, 0, 0, 0};
        for (std::uint32_t k = start[c]; k < start[c + 1]; ++k) {
            const std::uint32_t i = member[k];
            add_to_cell(grid, box.primary_image(x[i]), v[i], mass[species[i]], s);
        }
        for (int j = 0; j < kFieldSums; ++j) out[c * kFieldSums + j] = s[j];
    }
};

}  // namespace emergent::observe

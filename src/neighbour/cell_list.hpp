// SPDX-License-Identifier: MIT
// Cells over a domain and its ghost shell, for linear-cost neighbour search.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "emergent/vec3.hpp"

namespace emergent {

/// Regular cells over [lo - shell, hi + shell) whose faces fall on the domain faces, so every
/// cell is either inside the domain (holds owned particles only) or in the ghost shell (holds
/// ghosts only). Cells are at least range / subdivisions wide, so a pair closer than `range`
/// lies at most reach() cells apart along each axis (reach <= subdivisions). Finer cells
/// search a volume closer to the sphere of the range: 2 subdivisions test 125 cells of
/// (range/2)^3 instead of 27 of range^3, 42 % fewer candidates, for more cells to walk.
/// A position in single precision, relative to a cell grid's centre: the list search's copy.
struct BinnedPoint {
    float x, y, z;
};

class CellList {
public:
    void setup(const Vec3& lo, const Vec3& hi, double shell, double range, int subdivisions = 1);

    /// Linear index of the cell holding x (positions just outside the grid are clamped).
    int cell_of(const Vec3& x) const {
        int c[3];
        for (int d = 0; d < 3; ++d) {
            int k = static_cast<int>((x[d] - origin_[d]) * inverse_width_[d]);
            // The domain faces decide which side a point is on: rounding in the line above can
            // put a point lying on a face (a lattice start puts many there) one cell off, a
            // ghost into the domain or an owned particle into the shell.
            if (x[d] < lo_[d])
                k = std::min(k, first_inner_[d] - 1);
            else if (x[d] >= hi_[d])
                k = std::max(k, end_inner_[d]);
            else
                k = std::clamp(k, first_inner_[d], end_inner_[d] - 1);
            c[d] = k < 0 ? 0 : (k >= n_[d] ? n_[d] - 1 : k);
        }
        return (c[2] * n_[1] + c[1]) * n_[0] + c[0];
    }

    /// Order that sorts the first n particles by cell, and by id within a cell:
    /// order[k] = old index of new particle k. Depending only on positions and ids (not on the
    /// previous order) makes a restarted run retrace the original one bit for bit.
    void sort_order(const Vec3* x, const std::int64_t* id, std::size_t n,
                    std::vector<std::uint32_t>& order);

    /// Bins positions [0, n) into cells; members of a cell are listed in ascending index.
    void bin(const Vec3* x, std::size_t n);
    /// bin() right after sort_order(): positions [0, m) are the m particles that call ordered,
    /// permuted by its order and not moved since (the rest, e.g. ghosts, are new), so their
    /// cells are known and only the others are looked up. The same result as bin().
    void bin_after_sort(const Vec3* x, std::size_t n);

    Int3 shape() const { return {n_[0], n_[1], n_[2]}; }
    /// Cells to search on each side along each axis for pairs within the range.
    Int3 reach() const { return {reach_[0], reach_[1], reach_[2]}; }
    int n_cells() const { return n_[0] * n_[1] * n_[2]; }
    bool is_inner(int cell) const { return inner_[cell] != 0; }
    /// An inner cell whose whole search stencil (reach cells each way) is inner.
    bool is_deep(int cell) const { return inner_[cell] == 2; }
    const std::uint32_t* members_begin(int cell) const { return &members_[start_[cell]]; }
    const std::uint32_t* members_end(int cell) const { return &members_[start_[cell + 1]]; }
    /// Slots of cell c are [first(c), first(c + 1)) in members and binned positions.
    std::uint32_t first(int cell) const { return start_[cell]; }
    const std::uint32_t* members() const { return members_.data(); }
    /// Positions in cell order, in single precision relative to the grid's centre (a copy made
    /// by bin(), half the bytes of the positions), so a search streams through memory.
    const BinnedPoint* binned_positions() const { return binned_.data(); }
    /// Bound on the error of a distance between two binned positions (their rounding to single
    /// precision): a search widens its range by it, so it lists every pair the exact positions
    /// put in range (and a few just beyond, which cost nothing but a zero force).
    double binned_distance_error() const { return binned_error_; }
    /// Volume of the grid, ghost shell included.
    double grid_volume() const {
        return double(n_[0]) * n_[1] * n_[2] / (inverse_width_[0] * inverse_width_[1] * inverse_width_[2]);
    }

private:
    /// Cells of particles [known, n) into cell_ (those before are set), then the per-cell
    /// start offsets.
    void count(const Vec3* x, std::size_t n, std::size_t known = 0);

    Vec3 origin_{}, lo_{}, hi_{};
    double inverse_width_[3] = {1, 1, 1};
    int first_inner_[3] = {0, 0, 0}, end_inner_[3] = {1, 1, 1};  ///< inner cells per axis
    int n_[3] = {1, 1, 1};
    int reach_[3] = {1, 1, 1};
    std::vector<char> inner_;  ///< per cell: 0 ghost, 1 inner, 2 inner with its stencil inner
    std::vector<std::uint32_t> start_, members_, cell_;
    std::vector<std::uint32_t> sorted_cell_;  ///< cells of the last sort_order, in its order
    std::vector<BinnedPoint> binned_;
    Vec3 centre_{};
    double binned_error_ = 0;
};

}  // namespace emergent

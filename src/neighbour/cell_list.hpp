// SPDX-License-Identifier: MIT
// Cells over a domain and its ghost shell, for linear-cost neighbour search.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "emergent/vec3.hpp"

namespace emergent {

/// Where a position falls in a CellList's grid, as a value the back end's loops carry: the same
/// answer in a kernel as in the host's CellList::cell_of.
struct CellIndex {
    Vec3 origin{}, lo{}, hi{};
    Vec3 inverse_width{1, 1, 1};
    Int3 first_inner{0, 0, 0}, end_inner{1, 1, 1};  ///< inner cells per axis
    Int3 n{1, 1, 1};
    Int3 reach{1, 1, 1};

    /// Linear index of the cell holding x (positions just outside the grid are clamped).
    EMERGENT_HD int cell_of(const Vec3& x) const {
        int c[3];
        for (int d = 0; d < 3; ++d) {
            int k = static_cast<int>((x[d] - origin[d]) * inverse_width[d]);
            // The domain faces decide which side a point is on: rounding in the line above can
            // put a point lying on a face (a lattice start puts many there) one cell off, a
            // ghost into the domain or an owned particle into the shell.
            if (x[d] < lo[d])
                k = k < first_inner[d] - 1 ? k : first_inner[d] - 1;
            else if (x[d] >= hi[d])
                k = k > end_inner[d] ? k : end_inner[d];
            else
                k = k < first_inner[d] ? first_inner[d] : (k > end_inner[d] - 1 ? end_inner[d] - 1 : k);
            c[d] = k < 0 ? 0 : (k >= n[d] ? n[d] - 1 : k);
        }
        return (c[2] * n[1] + c[1]) * n[0] + c[0];
    }
    EMERGENT_HD int n_cells() const { return n[0] * n[1] * n[2]; }

    /// Calls visit(j) for the members j of every cell within reach of the cell holding x:
    /// cells z, y, x outermost first, members in slot order (cell c's are member[start[c] ..
    /// start[c + 1])). The one search order of the host's lists and the back end's.
    template <class Visit>
    EMERGENT_HD void visit_nearby(const Vec3& x, const std::uint32_t* start, const std::uint32_t* member,
                                  Visit& visit) const {
        visit_within(x, reach, start, member, visit);
    }

    /// Cells apart, along each axis, of two points closer than `range` (at most reach, at
    /// least 0): a search of a shorter range than the grid's visits fewer cells.
    EMERGENT_HD Int3 reach_of(double range) const {
        Int3 r;
        for (int d = 0; d < 3; ++d) {
            const double cells = range * inverse_width[d] - 1e-12;
            const int k = cells <= 0 ? 0 : static_cast<int>(cells) + (cells > static_cast<int>(cells) ? 1 : 0);
            r[d] = k < reach[d] ? k : reach[d];
        }
        return r;
    }

    /// visit_nearby() over the cells within `r` (at most reach) of the one holding x, in the
    /// same order: a shorter search visits a subsequence of the longer one's.
    template <class Visit>
    EMERGENT_HD void visit_within(const Vec3& x, const Int3& r, const std::uint32_t* start,
                                  const std::uint32_t* member, Visit& visit) const {
        const int c = cell_of(x);
        const int cx = c % n.x, cy = (c / n.x) % n.y, cz = c / (n.x * n.y);
        for (int dz = -r.z; dz <= r.z; ++dz)
            for (int dy = -r.y; dy <= r.y; ++dy)
                for (int dx = -r.x; dx <= r.x; ++dx) {
                    const int ax = cx + dx, ay = cy + dy, az = cz + dz;
                    if (ax < 0 || ay < 0 || az < 0 || ax >= n.x || ay >= n.y || az >= n.z) continue;
                    const int c2 = (az * n.y + ay) * n.x + ax;
                    for (std::uint32_t s = start[c2]; s < start[c2 + 1]; ++s) visit(member[s]);
                }
    }
};

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
    int cell_of(const Vec3& x) const { return index_.cell_of(x); }
    /// The grid as the back end's loops carry it.
    const CellIndex& index() const { return index_; }

    /// Order that sorts the first n particles by cell, and by id within a cell:
    /// order[k] = old index of new particle k. Depending only on positions and ids (not on the
    /// previous order) makes a restarted run retrace the original one bit for bit.
    void sort_order(const Vec3* x, const std::int64_t* id, std::size_t n,
                    std::vector<std::uint32_t>& order);

    /// After sort_order(): moves the particles for which first(old index) is true to the
    /// front of `order`, both parts keeping their cell order (and bin_after_sort() its cells);
    /// returns how many are in front.
    template <class Predicate>
    std::size_t partition_sorted(std::vector<std::uint32_t>& order, Predicate first) {
        std::vector<std::uint32_t> front, back;
        std::vector<std::uint32_t> front_cell, back_cell;
        for (std::size_t k = 0; k < order.size(); ++k) {
            const bool in_front = first(order[k]);
            (in_front ? front : back).push_back(order[k]);
            (in_front ? front_cell : back_cell).push_back(sorted_cell_[k]);
        }
        const std::size_t n_front = front.size();
        std::copy(front.begin(), front.end(), order.begin());
        std::copy(back.begin(), back.end(), order.begin() + static_cast<std::ptrdiff_t>(n_front));
        std::copy(front_cell.begin(), front_cell.end(), sorted_cell_.begin());
        std::copy(back_cell.begin(), back_cell.end(), sorted_cell_.begin() + static_cast<std::ptrdiff_t>(n_front));
        return n_front;
    }

    /// Bins positions [0, n) into cells; members of a cell are listed in ascending index.
    void bin(const Vec3* x, std::size_t n);
    /// bin() right after sort_order(): positions [0, m) are the m particles that call ordered,
    /// permuted by its order and not moved since (the rest, e.g. ghosts, are new), so their
    /// cells are known and only the others are looked up. The same result as bin().
    void bin_after_sort(const Vec3* x, std::size_t n);

    Int3 shape() const { return index_.n; }
    /// Cells to search on each side along each axis for pairs within the range.
    Int3 reach() const { return index_.reach; }
    int n_cells() const { return index_.n_cells(); }
    bool is_inner(int cell) const { return inner_[cell] != 0; }
    /// An inner cell whose whole search stencil (reach cells each way) is inner.
    bool is_deep(int cell) const { return inner_[cell] == 2; }
    const std::uint32_t* members_begin(int cell) const { return &members_[start_[cell]]; }
    const std::uint32_t* members_end(int cell) const { return &members_[start_[cell + 1]]; }
    /// Slots of cell c are [first(c), first(c + 1)) in members and binned positions.
    std::uint32_t first(int cell) const { return start_[cell]; }
    const std::uint32_t* members() const { return members_.data(); }
    /// first(c) for every cell and one past the last: n_cells() + 1 entries.
    const std::uint32_t* starts() const { return start_.data(); }
    /// Positions in cell order, in single precision relative to the grid's centre (a copy made
    /// by bin(), half the bytes of the positions), so a search streams through memory.
    const BinnedPoint* binned_positions() const { return binned_.data(); }
    /// Bound on the error of a distance between two binned positions (their rounding to single
    /// precision): a search widens its range by it, so it lists every pair the exact positions
    /// put in range (and a few just beyond, which cost nothing but a zero force).
    double binned_distance_error() const { return binned_error_; }
    /// Volume of the grid, ghost shell included.
    double grid_volume() const {
        const Int3& n = index_.n;
        const Vec3& w = index_.inverse_width;
        return double(n[0]) * n[1] * n[2] / (w[0] * w[1] * w[2]);
    }

private:
    /// Cells of particles [known, n) into cell_ (those before are set), then the per-cell
    /// start offsets.
    void count(const Vec3* x, std::size_t n, std::size_t known = 0);

    CellIndex index_;
    std::vector<char> inner_;  ///< per cell: 0 ghost, 1 inner, 2 inner with its stencil inner
    std::vector<std::uint32_t> start_, members_, cell_;
    std::vector<std::uint32_t> sorted_cell_;  ///< cells of the last sort_order, in its order
    std::vector<BinnedPoint> binned_;
    Vec3 centre_{};
    double binned_error_ = 0;
};

}  // namespace emergent

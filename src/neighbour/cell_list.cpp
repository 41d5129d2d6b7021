// SPDX-License-Identifier: MIT
// Cell list by counting sort.
#include "cell_list.hpp"

#include <algorithm>
#include <cmath>

#include "emergent/execution.hpp"

namespace emergent {

void CellList::setup(const Vec3& lo, const Vec3& hi, double shell, double range, int subdivisions) {
    CellIndex& g = index_;
    g.lo = lo;
    g.hi = hi;
    centre_ = 0.5 * (lo + hi);
    double min_cell = range / std::max(1, subdivisions);
    // A domain far larger than its particles need (a dilute gas in a huge box) would ask for
    // more cells than memory holds, and more than an int counts: wider cells then, as few as
    // kMostCells. Cells wider than asked stay correct (the search reaches fewer of them).
    constexpr double kMostCells = 1 << 24;
    for (int pass = 0; pass < 4; ++pass) {
        double cells = 1;
        for (int d = 0; d < 3; ++d) cells *= std::max(1.0, std::floor((hi[d] - lo[d]) / min_cell));
        if (cells <= kMostCells) break;
        min_cell *= 1.01 * std::cbrt(cells / kMostCells);
    }
    for (int d = 0; d < 3; ++d) {
        const double len = hi[d] - lo[d];
        const int inner = std::max(1, static_cast<int>(std::floor(len / min_cell)));
        const double width = len / inner;
        // A small domain may give cells wider than asked: then fewer are needed to span range.
        g.reach[d] = std::max(1, static_cast<int>(std::ceil(range / width - 1e-12)));
        // The shell must hold every cell the search reaches from an inner cell.
        const int layers = std::max(g.reach[d], static_cast<int>(std::ceil(shell / width - 1e-12)));
        g.n[d] = inner + 2 * layers;
        g.origin[d] = lo[d] - layers * width;
        g.first_inner[d] = layers;
        g.end_inner[d] = layers + inner;
        g.inverse_width[d] = 1.0 / width;
    }
    // Binned positions lie in the grid (owned in the domain, ghosts in the shell), within
    // `extent` of its centre in each coordinate. Each is rounded by at most extent 2^-24, a
    // difference by twice that, a distance by sqrt(3) times that; the float arithmetic of r^2
    // adds a few 2^-24 of the range. Doubled for margin (and for particles just outside the
    // grid): ~1e-6 of the grid's size.
    double extent = 0;
    for (int d = 0; d < 3; ++d) extent = std::max(extent, 0.5 * g.n[d] / g.inverse_width[d]);
    const double unit = std::ldexp(1.0, -24);
    binned_error_ = 2 * (2 * std::sqrt(3.0) * 2 * extent * unit + 4 * range * unit);
    inner_.assign(n_cells(), 0);
    // Mark cells that lie inside the domain: their index range excludes the ghost layers.
    for (int z = 0; z < g.n[2]; ++z)
        for (int y = 0; y < g.n[1]; ++y)
            for (int x = 0; x < g.n[0]; ++x) {
                const Vec3 centre{g.origin[0] + (x + 0.5) / g.inverse_width[0],
                                  g.origin[1] + (y + 0.5) / g.inverse_width[1],
                                  g.origin[2] + (z + 0.5) / g.inverse_width[2]};
                bool in = true;
                for (int d = 0; d < 3; ++d) in = in && centre[d] > lo[d] && centre[d] < hi[d];
                const int c[3] = {x, y, z};
                bool deep = in;
                for (int d = 0; d < 3; ++d)
                    deep = deep && c[d] - g.reach[d] >= g.first_inner[d] && c[d] + g.reach[d] < g.end_inner[d];
                inner_[(z * g.n[1] + y) * g.n[0] + x] = deep ? 2 : in ? 1 : 0;
            }
}

void CellList::count(const Vec3* x, std::size_t n, std::size_t known) {
    cell_.resize(n);
    start_.assign(n_cells() + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
        if (i >= known) cell_[i] = static_cast<std::uint32_t>(cell_of(x[i]));
        ++start_[cell_[i]];
    }
    // Counts to the first slot of each cell; the entry past the last cell is the total.
    start_[n_cells()] = exec::exclusive_scan(exec::Host{}, start_.data(), start_.data(),
                                             static_cast<std::size_t>(n_cells()));
}

void CellList::sort_order(const Vec3* x, const std::int64_t* id, std::size_t n,
                          std::vector<std::uint32_t>& order) {
    count(x, n);
    order.resize(n);
    std::vector<std::uint32_t> next(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) order[next[cell_[i]]++] = static_cast<std::uint32_t>(i);
    sorted_cell_.resize(n);
    for (std::size_t k = 0; k < n; ++k) sorted_cell_[k] = cell_[order[k]];
    // A cell holds a few particles: insertion sort by id is cheapest.
    for (int c = 0; c < n_cells(); ++c)
        for (std::uint32_t k = start_[c] + 1; k < start_[c + 1]; ++k) {
            const std::uint32_t moving = order[k];
            std::uint32_t j = k;
            for (; j > start_[c] && id[order[j - 1]] > id[moving]; --j) order[j] = order[j - 1];
            order[j] = moving;
        }
}

void CellList::bin(const Vec3* x, std::size_t n) {
    sorted_cell_.clear();  // positions may have moved: look every cell up
    bin_after_sort(x, n);
}

void CellList::bin_after_sort(const Vec3* x, std::size_t n) {
    const std::size_t known = std::min(n, sorted_cell_.size());
    cell_.resize(n);
    std::copy(sorted_cell_.begin(), sorted_cell_.begin() + known, cell_.begin());
    sorted_cell_.clear();  // good for one binning only
    count(x, n, known);
    members_.resize(n);
    binned_.resize(n);
    std::vector<std::uint32_t> next(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t slot = next[cell_[i]]++;
        members_[slot] = static_cast<std::uint32_t>(i);
        const Vec3 r = x[i] - centre_;
        binned_[slot] = {static_cast<float>(r.x), static_cast<float>(r.y), static_cast<float>(r.z)};
    }
}

}  // namespace emergent

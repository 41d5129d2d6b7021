// SPDX-License-Identifier: MIT
// Cost-based placement of the rank grid's cut planes.
#include "load_balance.hpp"

#include <algorithm>
#include <cmath>

#include "emergent/execution.hpp"

namespace emergent::decomp {

namespace {
/// Bins per domain of the cost profile: planes land within 1/64 of a domain before the
/// linear interpolation inside the bin.
constexpr int kBinsPerDomain = 64;

bool fits(const std::vector<double>& planes, const std::vector<double>& current, double min_width,
          double margin) {
    for (std::size_t k = 1; k < planes.size(); ++k)
        if (!(planes[k] - planes[k - 1] >= min_width)) return false;
    for (std::size_t k = 1; k + 1 < planes.size(); ++k)
        if (planes[k] < current[k - 1] + margin || planes[k] > current[k + 1] - margin) return false;
    return true;
}
}  // namespace

std::vector<double> equal_share_planes(const std::vector<long long>& profile, double lo, double hi,
                                       int parts) {
    const std::size_t bins = profile.size();
    const double width = (hi - lo) / static_cast<double>(bins);
    long long total = 0;
    for (long long c : profile) total += c;
    std::vector<double> planes(static_cast<std::size_t>(parts) + 1);
    planes.front() = lo;
    planes.back() = hi;
    long long below = 0;  // cost in bins [0, b)
    std::size_t b = 0;
    for (int k = 1; k < parts; ++k) {
        const double share = static_cast<double>(total) * k / parts;
        while (b < bins && static_cast<double>(below + profile[b]) < share) below += profile[b++];
        if (b == bins) {
            planes[k] = hi;
            continue;
        }
        const double into = profile[b] > 0 ? (share - static_cast<double>(below)) / static_cast<double>(profile[b]) : 0;
        planes[k] = lo + width * (static_cast<double>(b) + into);
    }
    return planes;
}

std::vector<double> reachable_planes(const std::vector<double>& current, const std::vector<double>& target,
                                     double min_width, double margin) {
    // The allowed planes form a convex set holding `current`: some point of the segment to
    // the target lies in it. Halving the step six times leaves a move of 1/64 of the way.
    std::vector<double> planes(current.size());
    for (double step = 1; step >= 1.0 / 64; step *= 0.5) {
        for (std::size_t k = 0; k < planes.size(); ++k)
            planes[k] = current[k] + step * (target[k] - current[k]);
        planes.front() = current.front();
        planes.back() = current.back();
        if (fits(planes, current, min_width, margin)) return planes;
    }
    return current;
}

BalanceReport balance_cuts(RankGrid& grid, const Vec3* position, const std::uint32_t* cost,
                           std::size_t n, double min_width, double margin) {
    BalanceReport report;
    report.imbalance_before = cost_imbalance(grid.comm(), cost, n);
    for (int d = 0; d < 3; ++d) {
        const int parts = grid.dims()[d];
        if (parts == 1) continue;
        const double lo = grid.global().lo[d], hi = grid.global().hi[d];
        std::vector<long long> profile(static_cast<std::size_t>(parts) * kBinsPerDomain, 0);
        const double scale = static_cast<double>(profile.size()) / (hi - lo);
        for (std::size_t i = 0; i < n; ++i) {
            // Particles a step outside the box (before a wall returns them) count at its edge.
            const double u = std::floor((position[i][d] - lo) * scale);
            const double last = static_cast<double>(profile.size() - 1);
            const auto b = static_cast<std::size_t>(u >= 0 ? std::min(u, last) : 0.0);
            profile[b] += cost[i];
        }
        exec::count_collective();
        MPI_Allreduce(MPI_IN_PLACE, profile.data(), static_cast<int>(profile.size()), MPI_LONG_LONG,
                      MPI_SUM, grid.comm());
        const std::vector<double> target = equal_share_planes(profile, lo, hi, parts);
        const std::vector<double> planes = reachable_planes(grid.cuts(d), target, min_width, margin);
        if (planes != grid.cuts(d)) {
            grid.set_cuts(d, planes);
            ++report.axes_moved;
        }
    }
    return report;
}

double cost_imbalance(MPI_Comm comm, const std::uint32_t* cost, std::size_t n) {
    long long local = 0;
    for (std::size_t i = 0; i < n; ++i) local += cost[i];
    long long most = 0, total = 0;
    int ranks = 1;
    MPI_Comm_size(comm, &ranks);
    exec::count_collective();
    MPI_Allreduce(&local, &most, 1, MPI_LONG_LONG, MPI_MAX, comm);
    exec::count_collective();
    MPI_Allreduce(&local, &total, 1, MPI_LONG_LONG, MPI_SUM, comm);
    return total > 0 ? static_cast<double>(most) * ranks / static_cast<double>(total) : 1.0;
}

}  // namespace emergent::decomp

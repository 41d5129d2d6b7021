// SPDX-License-Identifier: MIT
// Moving the rank grid's cut planes so that every slab of ranks carries an equal share of the work.
#pragma once

#include <cstdint>
#include <vector>

#include "rank_grid.hpp"

namespace emergent::decomp {

/// Work of one particle, in neighbour-list entries: its own entries (the pairs or contacts the
/// force loop visits for it) plus a fixed share for what is done once per particle
/// (integration, cell binning, walls, halo). Integers, so the global sums are exact and every
/// rank count and run computes the same planes.
constexpr std::uint32_t kParticleCost = 2;

/// What one rebalance did, the same on every rank.
struct BalanceReport {
    double imbalance_before = 1;  ///< max over ranks of their cost / mean cost, before
    int axes_moved = 0;           ///< axes whose planes moved
};

/// Moves the inner cut planes of every split axis of `grid` to where the cost profile along
/// that axis (summed over the other two axes and all ranks) is divided equally. Costs are
/// per owned particle. The planes stay such that every domain is at least `min_width` wide
/// (the ghost shell) and every particle within `margin` of its domain has its new owner next
/// door (so one migration pass moves it): where the equal division breaks these, the planes
/// move part of the way. Collective; deterministic (integer sums).
BalanceReport balance_cuts(RankGrid& grid, const Vec3* position, const std::uint32_t* cost,
                           std::size_t n, double min_width, double margin);

/// Max over ranks of the ranks' summed cost / mean: 1 is a perfect balance. Collective.
double cost_imbalance(MPI_Comm comm, const std::uint32_t* cost, std::size_t n);

/// The planes dividing a cost profile (bins of equal width over [lo, hi]) into `parts`
/// equal shares, linear within a bin: parts + 1 planes from lo to hi.
std::vector<double> equal_share_planes(const std::vector<long long>& profile, double lo, double hi,
                                       int parts);

/// `target` limited as balance_cuts says, starting from the valid planes `current`: the
/// farthest point of the way from current to target (halved until it fits) that keeps every
/// width >= min_width and plane k inside [current[k-1] + margin, current[k+1] - margin].
std::vector<double> reachable_planes(const std::vector<double>& current, const std::vector<double>& target,
                                     double min_width, double margin);

}  // namespace emergent::decomp

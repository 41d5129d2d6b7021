// SPDX-License-Identifier: MIT
// Bonds and clusters of rigid bodies from their attraction sites (the capsid model's
// bookkeeping; it exerts no force).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "emergent/box.hpp"
#include "emergent/vec3.hpp"

namespace emergent {

class Simulation;

/// Bodies i and j are bonded when, for one contact face of i, every site of that face lies
/// within `bond_range` of j's site of the partner type (paper: all four site pairs of two faces
/// within r_b = 0.5). Site type k is species first_site + k.
///
/// Two faces are in contact when every site pair lies within `contact_range` (>= bond_range).
/// Bonds define the clusters; contacts among a cluster's members decide whether it is closed
/// (a face touching a body outside the cluster closes nothing): in a closed shell
/// at temperature a bond or two is always stretched a little past r_b for a moment, and a
/// count of bonds alone then misses the shell, while a missing member leaves its neighbours'
/// faces with no partner site nearer than the closest faces that do not meet in the shell
/// (1.6-1.7 for the PW design; tests/physics/test_capsomer_shell.cpp).
struct SiteBondRule {
    int first_site = 1;
    std::vector<int> partner;
    std::vector<std::vector<int>> faces;
    double bond_range = 0.5;
    double contact_range = 1.0;
};

/// One site: where it is, its type (not species) and the id of its body.
struct SiteRecord {
    Vec3 x;
    int type = 0;
    std::int64_t body = -1;
};

/// The bond graph of every body that carries sites, and its connected components (clusters).
struct BondCensus {
    std::vector<std::int64_t> bodies;  ///< body ids, ascending
    std::vector<std::pair<int, int>> bonds;  ///< indices into `bodies`, first < second, sorted
    std::vector<int> degree;      ///< bonds per body
    std::vector<int> contacts;    ///< members of its own cluster in face contact (contact_range), >= degree
    std::vector<int> cluster;     ///< cluster index per body (clusters ordered by first member)
    std::vector<int> cluster_size;  ///< members per cluster

    /// Clusters of `size` members in which every member is in contact with `degree` others (a
    /// closed shell: 60 members, 5 contacts each).
    int complete_clusters(int size, int degree) const;
    /// The sizes, ascending, of the clusters of two or more members in which every member is in
    /// contact with `degree` others: closed shells of any size (the 60-member shell, and smaller
    /// cages the same particles can close into).
    std::vector<int> closed_cluster_sizes(int degree) const;
    int largest_cluster() const;
    /// Fraction of the bodies in clusters whose size lies in each group: group g holds sizes
    /// (upper[g-1], upper[g]] with upper[-1] = 0 (e.g. {1, 5, 50, 59, 60}).
    std::vector<double> mass_fractions(const std::vector<int>& upper) const;
};

/// How clusters changed between two censuses of the same bodies, tallied by size (entry n - 1
/// for clusters of n members, n up to the tally's length): each earlier cluster's successor is
/// the later cluster that holds most of its members (ties: the one found first). An earlier
/// cluster of n whose successor has n + 1 members `grew`, n - 1 `shrank`; `seen` counts the
/// earlier clusters of each size, so grew[n-1] / seen[n-1] is the chance that a cluster of n
/// gains one member within one interval, and grew / (grew + shrank) that a step is growth.
///
/// The rest count what a +-1 step misses. A piece is two or more members of an earlier cluster
/// that end up together in a later cluster other than its successor: `pieces` counts them by the
/// piece's size, `split` the earlier clusters (by size) that left one or more. `merged` counts the
/// earlier clusters of two or more whose successor also took a piece of two or more from another
/// earlier cluster; `assembled`, the later clusters of two or more (by size) made only of
/// earlier monomers. So pieces[k-1] against assembled[k-1] says whether the clusters of k that
/// appear come from larger ones breaking up or from monomers meeting.
struct ClusterEvents {
    std::vector<double> grew, shrank, seen;
    std::vector<double> split, pieces, merged, assembled;
    explicit ClusterEvents(std::size_t max_size = 0)
        : grew(max_size), shrank(max_size), seen(max_size), split(max_size), pieces(max_size),
          merged(max_size), assembled(max_size) {}
    void tally(const BondCensus& before, const BondCensus& after);
};

/// The bonds among the given sites; distances by the nearest image along periodic axes of
/// `box`. Every body that has a site is listed, bonded or not.
BondCensus find_site_bonds(const std::vector<SiteRecord>& sites, const SiteBondRule& rule,
                           const Box& box);

/// The same for a running simulation: gathers the sites of every rank (collective); the result
/// is the same on every rank.
BondCensus site_bond_census(const Simulation& sim, const SiteBondRule& rule);

}  // namespace emergent

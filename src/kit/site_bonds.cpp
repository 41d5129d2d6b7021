// SPDX-License-Identifier: MIT
// Bonds and clusters of bodies from their attraction sites.
#include "emergent/kit/site_bonds.hpp"

#include <mpi.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <set>
#include <stdexcept>

#include "emergent/error.hpp"
#include "emergent/simulation.hpp"

namespace emergent {

namespace {

/// Union-find with path halving.
int root(std::vector<int>& parent, int i) {
    while (parent[std::size_t(i)] != i) i = parent[std::size_t(i)] = parent[std::size_t(parent[std::size_t(i)])];
    return i;
}

}  // namespace

int BondCensus::complete_clusters(int size, int full_degree) const {
    std::vector<char> complete(cluster_size.size());
    for (std::size_t c = 0; c < cluster_size.size(); ++c) complete[c] = cluster_size[c] == size;
    for (std::size_t b = 0; b < bodies.size(); ++b)
        if (contacts[b] != full_degree) complete[std::size_t(cluster[b])] = 0;
    return int(std::count(complete.begin(), complete.end(), 1));
}

std::vector<int> BondCensus::closed_cluster_sizes(int full_degree) const {
    std::vector<char> closed(cluster_size.size());
    for (std::size_t c = 0; c < cluster_size.size(); ++c) closed[c] = cluster_size[c] >= 2;
    for (std::size_t b = 0; b < bodies.size(); ++b)
        if (contacts[b] != full_degree) closed[std::size_t(cluster[b])] = 0;
    std::vector<int> sizes;
    for (std::size_t c = 0; c < cluster_size.size(); ++c)
        if (closed[c]) sizes.push_back(cluster_size[c]);
    std::sort(sizes.begin(), sizes.end());
    return sizes;
}

int BondCensus::largest_cluster() const {
    return cluster_size.empty() ? 0 : *std::max_element(cluster_size.begin(), cluster_size.end());
}

std::vector<double> BondCensus::mass_fractions(const std::vector<int>& upper) const {
    std::vector<double> f(upper.size(), 0.0);
    if (bodies.empty()) return f;
    for (const int n : cluster_size) {
        int lower = 0;
        for (std::size_t g = 0; g < upper.size(); ++g) {
            if (n > lower && n <= upper[g]) f[g] += n;
            lower = upper[g];
        }
    }
    for (double& x : f) x /= double(bodies.size());
    return f;
}

void ClusterEvents::tally(const BondCensus& before, const BondCensus& after) {
    if (before.bodies != after.bodies)
        throw std::logic_error("cluster events: the censuses hold different bodies");
    const std::size_t n_before = before.cluster_size.size(), n_after = after.cluster_size.size();
    auto add = [](std::vector<double>& t, int n) {
        if (n >= 1 && std::size_t(n) <= t.size()) t[std::size_t(n - 1)] += 1;
    };
    // Each earlier cluster's members by later cluster: (later cluster, members) pairs.
    std::vector<std::vector<int>> later(n_before);
    for (std::size_t b = 0; b < before.bodies.size(); ++b)
        later[std::size_t(before.cluster[b])].push_back(after.cluster[b]);
    std::vector<std::vector<std::pair<int, int>>> parts(n_before);
    std::vector<int> successor(n_before, -1);
    // Per later cluster: the earlier clusters that gave it two or more members, and whether
    // every member was an earlier monomer.
    std::vector<int> pieces_in(n_after, 0);
    std::vector<char> from_monomers(n_after, 1);
    for (std::size_t c = 0; c < n_before; ++c) {
        std::vector<int>& to = later[c];
        std::sort(to.begin(), to.end());
        int best_count = 0;
        for (std::size_t k = 0; k < to.size();) {
            std::size_t e = k;
            while (e < to.size() && to[e] == to[k]) ++e;
            parts[c].emplace_back(to[k], int(e - k));
            if (int(e - k) > best_count) successor[c] = to[k], best_count = int(e - k);
            if (e - k >= 2) pieces_in[std::size_t(to[k])] += 1;
            if (before.cluster_size[c] > 1) from_monomers[std::size_t(to[k])] = 0;
            k = e;
        }
    }
    for (std::size_t c = 0; c < n_before; ++c) {
        const int n = before.cluster_size[c], d = successor[c];
        const int m = after.cluster_size[std::size_t(d)];
        add(seen, n);
        if (m == n + 1) add(grew, n);
        if (m == n - 1) add(shrank, n);
        bool left_piece = false;
        int own_at_successor = 0;
        for (const auto& [to, count] : parts[c]) {
            if (to == d) own_at_successor = count;
            else if (count >= 2) add(pieces, count), left_piece = true;
        }
        if (left_piece) add(split, n);
        if (own_at_successor >= 2 && pieces_in[std::size_t(d)] >= 2) add(merged, n);
    }
    for (std::size_t d = 0; d < n_after; ++d)
        if (after.cluster_size[d] >= 2 && from_monomers[d]) add(assembled, after.cluster_size[d]);
}

BondCensus find_site_bonds(const std::vector<SiteRecord>& sites, const SiteBondRule& rule,
                           const Box& box) {
    const int n_types = int(rule.partner.size());
    for (const std::vector<int>& face : rule.faces)
        for (const int t : face)
            if (t < 0 || t >= n_types) throw InputError("site bonds: face site type " + std::to_string(t) + " unknown");
    if (!(rule.bond_range > 0) || !(rule.contact_range >= rule.bond_range))
        throw InputError("site bonds: contact_range " + std::to_string(rule.contact_range) +
                         " must be at least bond_range " + std::to_string(rule.bond_range) + " > 0");
    BondCensus census;
    for (const SiteRecord& s : sites) census.bodies.push_back(s.body);
    std::sort(census.bodies.begin(), census.bodies.end());
    census.bodies.erase(std::unique(census.bodies.begin(), census.bodies.end()), census.bodies.end());
    const std::size_t n_bodies = census.bodies.size();
    auto index_of = [&](std::int64_t id) {
        return int(std::lower_bound(census.bodies.begin(), census.bodies.end(), id) - census.bodies.begin());
    };
    // site_of[body index * n_types + type]: the body's site of that type (a body has one of each
    // type it carries), -1 if none.
    std::vector<int> site_of(n_bodies * std::size_t(n_types), -1);
    std::vector<int> body_of(sites.size());
    std::vector<std::size_t> count(std::size_t(n_types), 0);
    std::size_t per_type = 1;  // the most sites of one type
    for (std::size_t s = 0; s < sites.size(); ++s) {
        if (sites[s].type < 0 || sites[s].type >= n_types)
            throw InputError("site bonds: site type " + std::to_string(sites[s].type) + " unknown");
        body_of[s] = index_of(sites[s].body);
        int& slot = site_of[std::size_t(body_of[s]) * std::size_t(n_types) + std::size_t(sites[s].type)];
        if (slot >= 0)
            throw InputError("site bonds: body " + std::to_string(sites[s].body) + " has two sites of type " +
                             std::to_string(sites[s].type));
        slot = int(s);
        per_type = std::max(per_type, ++count[std::size_t(sites[s].type)]);
    }

    // Sites binned by type and cell, in cells at least contact_range wide and, along each axis, no
    // more than twice the cube root of the sites per type: a type has about one site per body,
    // so a search meets about one site of the type it wants in its 27 cells, and the table of
    // cells stays within 8 entries per site whatever the box.
    const int side_cap = std::max(1, int(std::ceil(2 * std::cbrt(double(per_type)))));
    const Vec3 length = box.hi - box.lo;
    int n_cells[3];
    for (int d = 0; d < 3; ++d)
        n_cells[d] = std::max(1, std::min(side_cap, int(std::floor(length[d] / rule.contact_range))));
    const std::int64_t cells_per_type = std::int64_t(n_cells[0]) * n_cells[1] * n_cells[2];
    auto cell_of = [&](const Vec3& x, int d) {
        const int c = int(std::floor((x[d] - box.lo[d]) / length[d] * n_cells[d]));
        if (box.periodic[d]) return ((c % n_cells[d]) + n_cells[d]) % n_cells[d];
        return std::clamp(c, 0, n_cells[d] - 1);
    };
    auto key = [&](int cx, int cy, int cz, int type) {
        return std::int64_t(type) * cells_per_type + (std::int64_t(cx) * n_cells[1] + cy) * n_cells[2] + cz;
    };
    // Counting sort by key: first[k] .. first[k + 1] are the sites of one type in one cell.
    std::vector<std::uint32_t> first(std::size_t(cells_per_type * n_types + 1), 0), binned(sites.size());
    std::vector<std::int64_t> key_of(sites.size());
    for (std::size_t s = 0; s < sites.size(); ++s) {
        key_of[s] = key(cell_of(sites[s].x, 0), cell_of(sites[s].x, 1), cell_of(sites[s].x, 2), sites[s].type);
        ++first[std::size_t(key_of[s]) + 1];
    }
    std::partial_sum(first.begin(), first.end(), first.begin());
    {
        std::vector<std::uint32_t> next(first.begin(), first.end() - 1);
        for (std::size_t s = 0; s < sites.size(); ++s) binned[next[std::size_t(key_of[s])]++] = std::uint32_t(s);
    }
    auto separation = [&](Vec3 d) {
        for (int k = 0; k < 3; ++k)
            if (box.periodic[k]) {
                d[k] -= length[k] * std::nearbyint(d[k] / length[k]);
            }
        return d;
    };
    const double bond_sq = rule.bond_range * rule.bond_range, contact_sq = rule.contact_range * rule.contact_range;
    auto distance_sq = [&](int a, int b) {
        const Vec3 d = separation(sites[std::size_t(a)].x - sites[std::size_t(b)].x);
        return dot(d, d);
    };

    // For each body's face: the partners of its first site nearby, and of those the bodies whose
    // partner sites are near every site of the face (within bond_range: a bond; within
    // contact_range: a contact).
    std::set<std::pair<int, int>> bonds, touching;
    for (std::size_t i = 0; i < n_bodies; ++i)
        for (const std::vector<int>& face : rule.faces) {
            if (face.empty()) continue;
            const int lead = site_of[i * std::size_t(n_types) + std::size_t(face[0])];
            const int want = rule.partner[std::size_t(face[0])];
            if (lead < 0 || want < 0 || want >= n_types) continue;
            const Vec3& x = sites[std::size_t(lead)].x;
            const int c[3] = {cell_of(x, 0), cell_of(x, 1), cell_of(x, 2)};
            std::array<std::int64_t, 27> near;  // distinct neighbouring cells (few cells: images repeat)
            std::size_t n_near = 0;
            for (int dx = -1; dx <= 1; ++dx)
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dz = -1; dz <= 1; ++dz) {
                        int q[3] = {c[0] + dx, c[1] + dy, c[2] + dz};
                        bool inside = true;
                        for (int d = 0; d < 3; ++d) {
                            if (box.periodic[d]) q[d] = ((q[d] % n_cells[d]) + n_cells[d]) % n_cells[d];
                            else inside = inside && q[d] >= 0 && q[d] < n_cells[d];
                        }
                        if (inside) near[n_near++] = key(q[0], q[1], q[2], want);
                    }
            std::sort(near.begin(), near.begin() + std::ptrdiff_t(n_near));
            n_near = std::size_t(std::unique(near.begin(), near.begin() + std::ptrdiff_t(n_near)) - near.begin());
            for (std::size_t n = 0; n < n_near; ++n)
                for (std::uint32_t b = first[std::size_t(near[n])]; b < first[std::size_t(near[n]) + 1]; ++b) {
                    const int o = int(binned[b]);
                    const std::size_t j = std::size_t(body_of[std::size_t(o)]);
                    if (j == i) continue;
                    double widest = distance_sq(lead, o);  // the face's farthest site pair
                    for (std::size_t k = 1; k < face.size() && widest < contact_sq; ++k) {
                        const int mine = site_of[i * std::size_t(n_types) + std::size_t(face[k])];
                        const int p = rule.partner[std::size_t(face[k])];
                        const int theirs = p < 0 || p >= n_types ? -1 : site_of[j * std::size_t(n_types) + std::size_t(p)];
                        widest = mine >= 0 && theirs >= 0 ? std::max(widest, distance_sq(mine, theirs)) : contact_sq;
                    }
                    const std::pair<int, int> pair{int(std::min(i, j)), int(std::max(i, j))};
                    if (widest < contact_sq) touching.insert(pair);
                    if (widest < bond_sq) bonds.insert(pair);
                }
        }
    census.bonds.assign(bonds.begin(), bonds.end());
    census.degree.assign(n_bodies, 0);
    std::vector<int> parent(n_bodies);
    std::iota(parent.begin(), parent.end(), 0);
    for (const auto& [i, j] : census.bonds) {
        ++census.degree[std::size_t(i)], ++census.degree[std::size_t(j)];
        const int a = root(parent, i), b = root(parent, j);
        if (a != b) parent[std::size_t(std::max(a, b))] = std::min(a, b);
    }
    census.cluster.assign(n_bodies, -1);
    std::vector<int> number(n_bodies, -1);
    for (std::size_t b = 0; b < n_bodies; ++b) {
        const int r = root(parent, int(b));
        if (number[std::size_t(r)] < 0) {
            number[std::size_t(r)] = int(census.cluster_size.size());
            census.cluster_size.push_back(0);
        }
        census.cluster[b] = number[std::size_t(r)];
        ++census.cluster_size[std::size_t(number[std::size_t(r)])];
    }
    // Contacts within the cluster only: a face touching a body the cluster does not hold (a
    // member that just left, a monomer sitting in a gap) closes nothing.
    census.contacts.assign(n_bodies, 0);
    for (const auto& [i, j] : touching)
        if (census.cluster[std::size_t(i)] == census.cluster[std::size_t(j)])
            ++census.contacts[std::size_t(i)], ++census.contacts[std::size_t(j)];
    return census;
}

BondCensus site_bond_census(const Simulation& sim, const SiteBondRule& rule) {
    const ParticleStore& p = sim.particles();
    const int n_types = int(rule.partner.size());
    std::vector<double> mine;  // x, y, z, type, body per owned site
    if (p.has_rigid_fields())
        for (std::size_t i = 0; i < p.n_owned(); ++i) {
            const int t = p.species[i] - rule.first_site;
            if (p.body[i] < 0 || t < 0 || t >= n_types) continue;
            mine.insert(mine.end(), {p.position[i].x, p.position[i].y, p.position[i].z, double(t),
                                     double(p.body[i])});
        }
    const int ranks = sim.n_ranks();
    std::vector<int> counts(static_cast<std::size_t>(ranks)), offsets(static_cast<std::size_t>(ranks), 0);
    const int n_mine = int(mine.size());
    MPI_Allgather(&n_mine, 1, MPI_INT, counts.data(), 1, MPI_INT, sim.comm());
    for (int r = 1; r < ranks; ++r) offsets[std::size_t(r)] = offsets[std::size_t(r - 1)] + counts[std::size_t(r - 1)];
    std::vector<double> all(std::size_t(offsets.back() + counts.back()));
    MPI_Allgatherv(mine.data(), n_mine, MPI_DOUBLE, all.data(), counts.data(), offsets.data(), MPI_DOUBLE,
                   sim.comm());
    std::vector<SiteRecord> sites(all.size() / 5);
    for (std::size_t s = 0; s < sites.size(); ++s)
        sites[s] = {{all[5 * s], all[5 * s + 1], all[5 * s + 2]}, int(all[5 * s + 3]),
                    std::int64_t(all[5 * s + 4])};
    return find_site_bonds(sites, rule, sim.box());
}

}  // namespace emergent

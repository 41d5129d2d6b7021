// SPDX-License-Identifier: MIT
// The capsid model's particle and closed shell, against what the design must satisfy and
// against independent numbers (shared/notes/capsid-geometry.md, computed there with other
// code): the icosahedral group, coincident partner sites, the bond census of the exact shell
// and of shells with particles removed, the attraction energy through the force term (one and
// two ranks, the shell straddling the domain boundary) against a direct sum over site pairs,
// and the same after a rigid motion of the whole shell; the alternative PH design against the
// note's face, sphere count and shell energy.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <memory>
#include <numeric>
#include <set>
#include <utility>

#include "emergent/kit/capsomer.hpp"
#include "emergent/error.hpp"
#include "emergent/force_term.hpp"
#include "emergent/random.hpp"
#include "emergent/simulation.hpp"
#include "emergent/kit/site_bonds.hpp"

using namespace emergent;

namespace {

constexpr int kFirstSite = 1;
constexpr double kE = 0.09, kRa = 3, kRh = 0.3;

double norm(const Vec3& v) { return std::sqrt(dot(v, v)); }

/// Paper eq. 6, written out here apart from the force term's code.
double u_attraction(double r) {
    if (r >= kRa) return 0;
    if (r < kRh) return kE * (1 / (kRa * kRa) + r * r / std::pow(kRh, 4) - 2 / (kRh * kRh));
    return kE * (1 / (kRa * kRa) - 1 / (r * r));
}

struct Pose {
    Quat q;
    Vec3 shift;
};

/// Bodies of the design at the given poses (shell frame of particle 0 turned by q, moved by shift).
std::vector<SiteRecord> sites_at(const Capsomer& c, const std::vector<Pose>& poses) {
    std::vector<SiteRecord> s;
    for (std::size_t b = 0; b < poses.size(); ++b)
        for (std::size_t k = 0; k < c.sites.size(); ++k)
            s.push_back({rotate(poses[b].q, c.sites[k]) + poses[b].shift, int(k), std::int64_t(b)});
    return s;
}

double direct_energy(const Capsomer& c, const std::vector<SiteRecord>& s) {
    double u = 0;
    for (std::size_t i = 0; i < s.size(); ++i)
        for (std::size_t j = i + 1; j < s.size(); ++j)
            if (s[i].body != s[j].body && c.partner[std::size_t(s[i].type)] == s[j].type)
                u += u_attraction(norm(s[i].x - s[j].x));
    return u;
}

SiteBondRule bond_rule(const Capsomer& c) {
    SiteBondRule r;
    r.first_site = kFirstSite;
    r.partner = c.partner;
    r.faces = c.faces;
    r.bond_range = 0.5;
    return r;
}

std::vector<Pose> shell(const Pose& whole = {Quat{1, 0, 0, 0}, Vec3{0, 0, 0}}) {
    std::vector<Pose> p;
    for (const Quat& g : icosahedral_rotations()) p.push_back({whole.q * g, whole.shift});
    return p;
}

Box big_box() {
    Box b;
    b.lo = {0, 0, 0};
    b.hi = {40, 40, 40};
    return b;
}

/// The design's site attraction at strength `epsilon`.
SiteAttraction attraction(const Capsomer& c, double epsilon) {
    SiteAttraction a;
    a.first_site = kFirstSite;
    a.partner = c.partner;
    a.epsilon = epsilon;
    return a;
}

/// The design's bodies at `poses` (with velocity[b] where given, else at rest): one body kind of
/// its spheres (species 0, diameter 1) and massless sites, body ids from 0. Returns the first
/// particle id after the bodies' constituents.
std::int64_t add_capsomers(Simulation& sim, const Capsomer& c, const std::vector<Pose>& poses,
                           const std::vector<Vec3>& velocity = {}) {
    std::vector<Vec3> x = c.spheres;
    x.insert(x.end(), c.sites.begin(), c.sites.end());
    std::vector<int> sp(c.spheres.size(), 0);
    std::vector<double> d(c.spheres.size(), 1.0);
    for (std::size_t k = 0; k < c.sites.size(); ++k) sp.push_back(kFirstSite + int(k)), d.push_back(0.0);
    const int kind = sim.add_body_kind(x, sp, d);
    Vec3 centre{0, 0, 0};
    for (const Vec3& s : c.spheres) centre += s;
    centre *= 1.0 / double(c.spheres.size());
    const std::int64_t per = std::int64_t(x.size());
    for (std::size_t b = 0; b < poses.size(); ++b)
        sim.add_body(kind, rotate(poses[b].q, centre) + poses[b].shift, poses[b].q,
                     b < velocity.size() ? velocity[b] : Vec3{0, 0, 0}, {0, 0, 0}, std::int64_t(b),
                     std::int64_t(b) * per);
    return std::int64_t(poses.size()) * per;
}

/// Potential energy of the bodies at `poses` through the engine (no solvent, at rest).
double engine_energy(const Capsomer& c, const std::vector<Pose>& poses, double epsilon) {
    RunSettings rs;
    Simulation sim(MPI_COMM_WORLD, rs);
    sim.set_box(big_box());
    std::vector<double> masses{1.5};  // species 0: spheres; then the massless sites
    masses.resize(kFirstSite + c.sites.size(), 0.0);
    sim.set_species_masses(masses);
    sim.add_force(make_soft_spheres_and_sites(attraction(c, epsilon)));
    add_capsomers(sim, c, poses);
    sim.initialise();
    const ThermoSample t = sim.measure();
    return t.potential * double(t.n);
}

/// Particle 0 of the closed shell against the other 59: how many of its sites coincide with
/// their partner (distance < 1e-9), the closest partner site that does not, and the closest
/// sphere of another particle.
struct ShellContacts {
    int coincident = 0;
    double closest_other = 1e300, closest_sphere = 1e300;
};
ShellContacts shell_contacts(const Capsomer& c) {
    const std::vector<Quat> g = icosahedral_rotations();
    ShellContacts r;
    for (std::size_t a = 1; a < g.size(); ++a) {
        for (std::size_t i = 0; i < c.sites.size(); ++i) {
            const double d = norm(c.sites[i] - rotate(g[a], c.sites[std::size_t(c.partner[i])]));
            if (d < 1e-9) ++r.coincident;
            else r.closest_other = std::min(r.closest_other, d);
        }
        for (const Vec3& p : c.spheres)
            for (const Vec3& q : c.spheres) r.closest_sphere = std::min(r.closest_sphere, norm(p - rotate(g[a], q)));
    }
    return r;
}

}  // namespace

TEST(Capsomer, IcosahedralGroup) {
    const std::vector<Quat> g = icosahedral_rotations();
    ASSERT_EQ(g.size(), 60u);
    std::map<int, int> orders;
    for (const Quat& q : g) {
        // Closed under products: every product is one of the 60.
        for (const Quat& r : g) {
            const Quat p = q * r;
            int found = 0;
            for (const Quat& s : g) found += std::fabs(std::fabs(dot(p, s)) - 1) < 1e-12;
            ASSERT_EQ(found, 1);
        }
        Quat p = q;
        int n = 1;
        while (std::fabs(std::fabs(p.w) - 1) > 1e-12 && n < 10) p = p * q, ++n;
        ++orders[n];
    }
    EXPECT_EQ(orders, (std::map<int, int>{{1, 1}, {2, 15}, {3, 20}, {5, 24}}));
}

TEST(Capsomer, ShellGeometry) {
    const Capsomer c = pw_capsomer();
    EXPECT_NEAR(c.face_distance, 4.761296, 1e-6);  // the note's R_f
    ASSERT_EQ(c.sites.size(), 20u);
    ASSERT_EQ(c.faces.size(), 5u);
    // Every site of every particle meets exactly one partner site of another particle at
    // distance 0 (600 pairs), and no other partner comes within the bond range.
    const auto [coincident, closest_other, closest_sphere] = shell_contacts(c);
    // Particle 0's 20 sites, each meeting one partner: with the 60 symmetric copies, 600
    // coincident site pairs in the shell (each pair counted from both ends).
    EXPECT_EQ(coincident, 20);
    EXPECT_GT(closest_other, 0.5);  // the bond range r_b
    // Spheres of different particles never overlap in the shell: beyond the WCA range.
    EXPECT_GT(closest_sphere, 1.122462048309373);
    // Within a particle no gap lets a solvent atom (diameter 1) in: neighbours < 0.55 apart.
    for (const Vec3& p : c.spheres) {
        double nearest = 1e300;
        for (const Vec3& q : c.spheres)
            if (norm(p - q) > 0) nearest = std::min(nearest, norm(p - q));
        EXPECT_LT(nearest, 0.55);
    }
}

TEST(Capsomer, BondCensusOfTheExactShell) {
    const Capsomer c = pw_capsomer();
    const BondCensus full = find_site_bonds(sites_at(c, shell({Quat{1, 0, 0, 0}, {20, 20, 20}})), bond_rule(c), big_box());
    EXPECT_EQ(full.bodies.size(), 60u);
    EXPECT_EQ(full.bonds.size(), 150u);
    for (const int d : full.degree) EXPECT_EQ(d, 5);
    EXPECT_EQ(full.cluster_size, std::vector<int>{60});
    EXPECT_EQ(full.complete_clusters(60, 5), 1);
    EXPECT_EQ(full.closed_cluster_sizes(5), std::vector<int>{60});
    EXPECT_EQ(full.contacts, full.degree);
    EXPECT_EQ(full.mass_fractions({1, 5, 50, 59, 60}), (std::vector<double>{0, 0, 0, 0, 1}));

    // One particle removed: its 5 bonds go, a 59-cluster that is no shell.
    std::vector<Pose> poses = shell({Quat{1, 0, 0, 0}, {20, 20, 20}});
    std::vector<Pose> open(poses.begin(), poses.end() - 1);
    const BondCensus less = find_site_bonds(sites_at(c, open), bond_rule(c), big_box());
    EXPECT_EQ(less.bonds.size(), 145u);
    EXPECT_EQ(less.cluster_size, std::vector<int>{59});
    EXPECT_EQ(less.complete_clusters(60, 5), 0);
    EXPECT_TRUE(less.closed_cluster_sizes(5).empty());

    // Particle 0's five neighbours removed: it is left alone, beside a 54-cluster.
    std::set<int> neighbours;
    for (const auto& [i, j] : full.bonds)
        if (i == 0) neighbours.insert(j);
    ASSERT_EQ(neighbours.size(), 5u);
    std::vector<Pose> holed;
    for (int b = 0; b < 60; ++b)
        if (!neighbours.count(b)) holed.push_back(poses[std::size_t(b)]);
    const BondCensus apart = find_site_bonds(sites_at(c, holed), bond_rule(c), big_box());
    // Each removed particle took its 5 bonds; no two of them are bonded (a bond between two
    // of particle 0's neighbours would close a triangle with it; fully bonded trimers exist,
    // so count the shared bonds instead of assuming none).
    int shared = 0;
    for (const auto& [i, j] : full.bonds) shared += neighbours.count(i) && neighbours.count(j);
    EXPECT_EQ(apart.bonds.size(), 150u - 25u + std::size_t(shared));
    EXPECT_EQ(apart.largest_cluster(), 54);
    EXPECT_EQ(apart.cluster_size.size(), 2u);
    EXPECT_EQ(apart.degree[0], 0);
    // Neither the 54-cluster nor the lone particle is a closed cage.
    EXPECT_TRUE(apart.closed_cluster_sizes(5).empty());
    EXPECT_EQ(apart.closed_cluster_sizes(0), std::vector<int>{});
}

TEST(Capsomer, ShellAcrossThePeriodicBoundary) {
    // The same census when the shell sits on the box's corner (sites wrapped into the box).
    const Capsomer c = pw_capsomer();
    std::vector<SiteRecord> s = sites_at(c, shell({Quat{1, 0, 0, 0}, {0.5, 39.7, 0.2}}));
    for (SiteRecord& r : s)
        for (int d = 0; d < 3; ++d) r.x[d] -= 40 * std::floor(r.x[d] / 40);
    Box box = big_box();
    const BondCensus wrapped = find_site_bonds(s, bond_rule(c), box);
    EXPECT_EQ(wrapped.bonds.size(), 150u);
    EXPECT_EQ(wrapped.complete_clusters(60, 5), 1);
}

// The census against the rule applied by brute force (every face of every body against every
// other body, nearest images): three shells, two straddling the periodic boundary, each
// capsomer shaken by its own small rigid motion so that some bonds hold and some break.
TEST(Capsomer, BondCensusAgreesWithBruteForceOnShakenShells) {
    const Capsomer c = pw_capsomer();
    const SiteBondRule rule = bond_rule(c);
    Box box = big_box();
    std::vector<Pose> poses;
    for (const Vec3& at : {Vec3{20, 20, 20}, Vec3{0.5, 39.7, 0.2}, Vec3{38, 9, 21}})
        for (const Pose& p : shell({Quat{1, 0, 0, 0}, at})) poses.push_back(p);
    for (std::size_t b = 0; b < poses.size(); ++b) {
        const Vec3 turn{gaussian(11, b, 0), gaussian(11, b, 1), gaussian(11, b, 2)};
        const Quat q = axis_angle(turn, 0.03 * norm(turn));  // ~0.05 rad: sites ~4 out move ~0.2
        const Vec3 centre = rotate(poses[b].q, Vec3{0, 0, 0}) + poses[b].shift;
        poses[b].q = normalized(q * poses[b].q);
        poses[b].shift = rotate(q, poses[b].shift - centre) + centre +
                         0.08 * Vec3{gaussian(12, b, 0), gaussian(12, b, 1), gaussian(12, b, 2)};
    }
    std::vector<SiteRecord> s = sites_at(c, poses);
    for (SiteRecord& r : s)
        for (int d = 0; d < 3; ++d) r.x[d] -= 40 * std::floor(r.x[d] / 40);
    // Brute force: body i's face f is bonded to body j when each of its sites lies within the
    // bond range of j's site of the partner type.
    std::map<std::pair<std::int64_t, int>, Vec3> where;
    for (const SiteRecord& r : s) where[{r.body, r.type}] = r.x;
    auto apart = [](Vec3 d) {
        for (int k = 0; k < 3; ++k) d[k] -= 40 * std::round(d[k] / 40);
        return norm(d);
    };
    std::set<std::pair<int, int>> expected;
    const int n = int(poses.size());
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            if (i == j) continue;
            for (const std::vector<int>& face : c.faces) {
                bool all = true;
                for (const int t : face)
                    all = all && apart(where.at({i, t}) - where.at({j, c.partner[std::size_t(t)]})) < rule.bond_range;
                if (all) expected.insert({std::min(i, j), std::max(i, j)});
            }
        }
    const BondCensus census = find_site_bonds(s, rule, box);
    const std::set<std::pair<int, int>> found(census.bonds.begin(), census.bonds.end());
    EXPECT_EQ(found, expected);
    // The shaking must leave the test something to tell apart: some bonds broken, most kept.
    EXPECT_LT(expected.size(), 450u);
    EXPECT_GT(expected.size(), 225u);
    // Contacts the same way with contact_range: per body, the others one of its faces touches.
    std::vector<std::set<int>> touching(std::size_t(n), std::set<int>{});
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (const std::vector<int>& face : c.faces) {
                bool all = i != j;
                for (const int t : face)
                    all = all && apart(where.at({i, t}) - where.at({j, c.partner[std::size_t(t)]})) < rule.contact_range;
                if (all) touching[std::size_t(i)].insert(j), touching[std::size_t(j)].insert(i);
            }
    int more = 0;  // bodies with a contact that is no bond: the shaking reaches past r_b
    for (int i = 0; i < n; ++i) {
        int mates = 0;  // contacts count within the body's own cluster
        for (const int j : touching[std::size_t(i)]) mates += census.cluster[std::size_t(j)] == census.cluster[std::size_t(i)];
        EXPECT_EQ(census.contacts[std::size_t(i)], mates) << "body " << i;
        more += census.contacts[std::size_t(i)] > census.degree[std::size_t(i)];
    }
    EXPECT_GT(more, 0);
}

// A closed shell at temperature has a bond stretched past r_b now and then. Two neighbours
// moved 0.3 apart each: their bond's site pairs are 0.6 apart, their other bonds' 0.3. The
// shell is one cluster of 60 with 149 bonds, and closed by its contacts; counted by bonds alone
// (contact_range = bond_range) it would not be.
TEST(Capsomer, ClosedShellWithAStretchedBond) {
    const Capsomer c = pw_capsomer();
    std::vector<Pose> poses = shell({Quat{1, 0, 0, 0}, {20, 20, 20}});
    const BondCensus exact = find_site_bonds(sites_at(c, poses), bond_rule(c), big_box());
    int k = -1;
    for (const auto& [i, j] : exact.bonds)
        if (i == 0) k = j;
    ASSERT_GT(k, 0);
    auto centre = [&](int b) {
        Vec3 m{0, 0, 0};
        for (const Vec3& x : c.spheres) m += rotate(poses[std::size_t(b)].q, x);
        return (1.0 / double(c.spheres.size())) * m;
    };
    const Vec3 u = (1.0 / norm(centre(0) - centre(k))) * (centre(0) - centre(k));
    poses[0].shift += 0.3 * u;
    poses[std::size_t(k)].shift -= 0.3 * u;
    const BondCensus stretched = find_site_bonds(sites_at(c, poses), bond_rule(c), big_box());
    EXPECT_EQ(stretched.bonds.size(), 149u);
    EXPECT_EQ(stretched.cluster_size, std::vector<int>{60});
    EXPECT_EQ(stretched.degree[0], 4);
    EXPECT_EQ(stretched.degree[std::size_t(k)], 4);
    for (const int n : stretched.contacts) EXPECT_EQ(n, 5);
    EXPECT_EQ(stretched.complete_clusters(60, 5), 1);
    EXPECT_EQ(stretched.closed_cluster_sizes(5), std::vector<int>{60});
    SiteBondRule strict = bond_rule(c);
    strict.contact_range = strict.bond_range;
    EXPECT_EQ(find_site_bonds(sites_at(c, poses), strict, big_box()).complete_clusters(60, 5), 0);
    // A member moved 0.7 straight out: its bonds break (site pairs 0.7 apart) but its faces
    // still touch the hole's rim within 1.0. It is a monomer now, and contacts count within a
    // cluster, so neither it nor the 59-cluster around the hole is closed.
    {
        std::vector<Pose> lifted = shell({Quat{1, 0, 0, 0}, {20, 20, 20}});
        const Vec3 out = centre(59);
        lifted[59].shift += (0.7 / norm(out)) * out;
        const BondCensus apart = find_site_bonds(sites_at(c, lifted), bond_rule(c), big_box());
        EXPECT_EQ(apart.largest_cluster(), 59);
        EXPECT_EQ(apart.degree[59], 0);
        EXPECT_EQ(apart.contacts[59], 0);
        EXPECT_TRUE(apart.closed_cluster_sizes(5).empty());
    }
}

// A missing member leaves its neighbours' faces with no partner site nearby. The nearest faces
// that do not meet in the closed shell are 1.60 apart with this design (the note's rows; 1.69
// with the scene's default rows, which its design check reports), so up to 1.5 the 59-cluster
// is not closed and the default contact range, 1.0, cannot close an open shell; past 1.60 every
// member gains a contact that is no neighbour, which shows the test can tell.
TEST(Capsomer, OpenShellIsNotClosedAtWideContactRanges) {
    const Capsomer c = pw_capsomer();
    const std::vector<Pose> poses = shell({Quat{1, 0, 0, 0}, {20, 20, 20}});
    const std::vector<Pose> open(poses.begin(), poses.end() - 1);
    auto census_at = [&](double range) {
        SiteBondRule rule = bond_rule(c);
        rule.contact_range = range;
        return find_site_bonds(sites_at(c, open), rule, big_box());
    };
    for (const double range : {1.0, 1.25, 1.5}) {
        const BondCensus census = census_at(range);
        EXPECT_EQ(census.cluster_size, std::vector<int>{59}) << range;
        int short_of_one = 0;  // the hole's five neighbours
        for (const int n : census.contacts) short_of_one += n == 4;
        EXPECT_EQ(short_of_one, 5) << range;
        EXPECT_TRUE(census.closed_cluster_sizes(5).empty()) << range;
    }
    int beyond = 0;
    for (const int n : census_at(1.65).contacts) beyond += n > 5;
    EXPECT_EQ(beyond, 59);
    SiteBondRule narrow = bond_rule(c);
    narrow.contact_range = 0.4;
    EXPECT_THROW(find_site_bonds(sites_at(c, open), narrow, big_box()), InputError);
}

// A body with two sites of one type has no partner site to pair each of its face's sites with:
// refused, naming the body and the type.
TEST(Capsomer, BondCensusRefusesTwoSitesOfOneTypeOnABody) {
    const Capsomer c = pw_capsomer();
    std::vector<SiteRecord> s = sites_at(c, {{Quat{1, 0, 0, 0}, {20, 20, 20}}});
    s.push_back(s.front());
    try {
        find_site_bonds(s, bond_rule(c), big_box());
        FAIL() << "two sites of one type on a body were accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("body 0 has two sites of type 0"), std::string::npos) << e.what();
    }
}

TEST(Capsomer, AttractionEnergyOfShellAndDimers) {
    const Capsomer c = pw_capsomer();
    // The shell at the box's centre, where the domains of 2 ranks meet, turned and moved by a
    // random rigid motion: the energy is that of the note (-1272.56 at e = 0.09, computed with
    // other code), the direct sum's, and the bonds are the same.
    const Pose whole{normalized(Quat{gaussian(7, 1, 0), gaussian(7, 1, 1), gaussian(7, 1, 2), gaussian(7, 1, 3)}),
                     {20.31, 19.87, 20.05}};
    const std::vector<Pose> poses = shell(whole);
    const double direct = direct_energy(c, sites_at(c, poses));
    EXPECT_NEAR(direct, -1272.56, 0.005);  // the note gives 2 decimals
    const double engine = engine_energy(c, poses, kE);
    // The force term against the direct sum: the same pairs summed in another order.
    EXPECT_NEAR(engine, direct, 1e-9 * std::fabs(direct));
    EXPECT_EQ(find_site_bonds(sites_at(c, poses), bond_rule(c), big_box()).bonds.size(), 150u);
    // No attraction: spheres of neighbours lie beyond the WCA range, so the energy is 0.
    EXPECT_EQ(engine_energy(c, poses, 0.0), 0.0);

    // Each of particle 0's five bonded neighbours alone with it: the note's isolated pair
    // energies (5-fold -8.198 twice, 3-fold -8.325 twice, 2-fold -8.044), and bonded.
    const BondCensus full = find_site_bonds(sites_at(c, poses), bond_rule(c), big_box());
    std::multiset<double> energies;
    for (const auto& [i, j] : full.bonds) {
        if (i != 0) continue;
        const std::vector<Pose> pair{poses[0], poses[std::size_t(j)]};
        const double u = engine_energy(c, pair, kE);
        EXPECT_NEAR(u, direct_energy(c, sites_at(c, pair)), 1e-9);
        energies.insert(std::round(u * 1000) / 1000);
        EXPECT_EQ(find_site_bonds(sites_at(c, pair), bond_rule(c), big_box()).bonds.size(), 1u);
    }
    EXPECT_EQ(energies, (std::multiset<double>{-8.325, -8.325, -8.198, -8.198, -8.044}));
}

TEST(Capsomer, ClusterEventsBySize) {
    // Bodies 0..4: {0, 1} and {2, 3} and {4}, then {0, 1, 4} and {2} and {3}.
    BondCensus before, after;
    before.bodies = after.bodies = {0, 1, 2, 3, 4};
    before.cluster = {0, 0, 1, 1, 2};
    before.cluster_size = {2, 2, 1};
    after.cluster = {0, 0, 1, 2, 0};
    after.cluster_size = {3, 1, 1};
    ClusterEvents e(60);
    e.tally(before, after);
    EXPECT_EQ(e.seen[1], 2);   // two pairs before
    EXPECT_EQ(e.grew[1], 1);   // {0, 1} -> {0, 1, 4}
    EXPECT_EQ(e.shrank[1], 1); // {2, 3} -> {2} (ties: the first found)
    EXPECT_EQ(e.seen[0], 1);   // the monomer 4, absorbed: a jump 1 -> 3, neither
    EXPECT_EQ(e.grew[0] + e.shrank[0], 0);
    for (const auto* t : {&e.split, &e.pieces, &e.merged, &e.assembled})
        EXPECT_EQ(std::accumulate(t->begin(), t->end(), 0.0), 0);  // only single members moved
    BondCensus other = after;
    other.bodies = {0, 1, 2, 3, 5};
    EXPECT_THROW(e.tally(before, other), std::logic_error);
}

TEST(Capsomer, ClusterEventsPiecesAndMergers) {
    // Bodies 0..11: {0..5}, {6, 7}, {8}, {9}, {10, 11}, then {0..3, 6, 7} (the six lost the
    // piece {4, 5} and took the pair {6, 7}), {4, 5}, {8, 9} (two monomers met), {10}, {11}.
    BondCensus before, after;
    before.bodies = after.bodies = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11};
    before.cluster = {0, 0, 0, 0, 0, 0, 1, 1, 2, 3, 4, 4};
    before.cluster_size = {6, 2, 1, 1, 2};
    after.cluster = {0, 0, 0, 0, 1, 1, 0, 0, 2, 2, 3, 4};
    after.cluster_size = {6, 2, 2, 1, 1};
    ClusterEvents e(60);
    e.tally(before, after);
    EXPECT_EQ(e.seen[5], 1);
    EXPECT_EQ(e.split[5], 1);     // the six left a piece
    EXPECT_EQ(e.pieces[1], 1);    // of two: {4, 5}
    EXPECT_EQ(e.merged[5], 1);    // the six's successor took the pair
    EXPECT_EQ(e.merged[1], 1);    // and the pair's successor is the same cluster
    EXPECT_EQ(e.assembled[1], 1); // {8, 9}
    EXPECT_EQ(e.grew[0], 2);      // 8 and 9 each joined a monomer
    EXPECT_EQ(e.shrank[1], 1);    // {10, 11} fell apart into monomers: a step, not a piece
    EXPECT_EQ(e.grew[5] + e.shrank[5], 0);  // 6 -> 6 by a swap
    const double all_pieces = std::accumulate(e.pieces.begin(), e.pieces.end(), 0.0);
    const double all_splits = std::accumulate(e.split.begin(), e.split.end(), 0.0);
    EXPECT_EQ(all_pieces, 1);
    EXPECT_EQ(all_splits, 1);
    EXPECT_EQ(std::accumulate(e.assembled.begin(), e.assembled.end(), 0.0), 1);
}

TEST(Capsomer, PentagonalHexecontahedronDesign) {
    // The PH face against the note's vertices (computed there with other code), to the 6
    // decimals it gives; five contacts meeting five neighbours as in PW.
    const Capsomer c = ph_capsomer();
    const std::vector<Vec3> note{{0, 4.119307, 6.665178}, {2.911648, 2.003724, 6.583845},
                                 {4.489803, 2.570624, 5.391955}, {4.314303, 4.314303, 4.314303},
                                 {2.570624, 5.391955, 4.489803}};
    ASSERT_EQ(c.outer_face.size(), 5u);
    for (std::size_t k = 0; k < 5; ++k) EXPECT_LT(norm(c.outer_face[k] - note[k]), 2e-6) << "V" << k;
    EXPECT_NEAR(c.face_distance, 7.20, 0.005);  // the note: "outer face at 7.20"
    // Planar, at the face distance.
    Vec3 normal = cross(c.outer_face[1] - c.outer_face[0], c.outer_face[2] - c.outer_face[0]);
    normal *= 1 / norm(normal);
    for (const Vec3& v : c.outer_face) EXPECT_NEAR(std::fabs(dot(normal, v)), c.face_distance, 1e-9);
    ASSERT_EQ(c.sites.size(), 20u);
    const auto [coincident, closest_other, closest_sphere] = shell_contacts(c);
    EXPECT_EQ(coincident, 20);
    EXPECT_GT(closest_other, 0.5);
    // The note: spheres of different particles at least 1.140 apart (2 x the inset 0.57).
    EXPECT_NEAR(closest_sphere, 1.140, 0.0005);
    // The note's count, 18 + 14. Each layer (0.5 and 1.2 below the face, inset 0.57 from the
    // lateral planes) is covered to 0.55: no point of it is farther from a sphere centre, so
    // no solvent atom (WCA range 1.12) fits through; checked on a grid of spacing 0.02.
    EXPECT_EQ(c.spheres.size(), 32u);
    std::vector<Vec3> inward;
    Vec3 middle{0, 0, 0};
    for (const Vec3& v : c.outer_face) middle += 0.2 * v;
    for (std::size_t k = 0; k < 5; ++k) {
        Vec3 m = cross(c.outer_face[k], c.outer_face[(k + 1) % 5]);
        m *= (dot(m, middle) > 0 ? 1 : -1) / norm(m);
        inward.push_back(m);
    }
    const Vec3 n = dot(normal, middle) > 0 ? normal : -1.0 * normal;
    const Vec3 e1 = (1 / norm(c.outer_face[1] - c.outer_face[0])) * (c.outer_face[1] - c.outer_face[0]);
    const Vec3 e2 = cross(n, e1);
    double worst = 0;
    int points = 0;
    for (const double depth : {0.5, 1.2}) {
        const Vec3 origin = ((c.face_distance - depth) / c.face_distance) * middle;
        for (double s = -4; s <= 4; s += 0.02)
            for (double t = -4; t <= 4; t += 0.02) {
                const Vec3 x = origin + s * e1 + t * e2;
                bool inside = true;
                for (const Vec3& m : inward) inside = inside && dot(m, x) >= 0.57;
                if (!inside) continue;
                ++points;
                double nearest = 1e300;
                for (const Vec3& q : c.spheres) nearest = std::min(nearest, norm(x - q));
                worst = std::max(worst, nearest);
            }
    }
    EXPECT_GT(points, 1000);
    EXPECT_LE(worst, 0.55 + 1e-3);  // the construction's grid is 0.01 fine
    const BondCensus shell_census =
        find_site_bonds(sites_at(c, shell({Quat{1, 0, 0, 0}, {20, 20, 20}})), bond_rule(c), big_box());
    EXPECT_EQ(shell_census.bonds.size(), 150u);
    for (const int d : shell_census.degree) EXPECT_EQ(d, 5);
    EXPECT_EQ(shell_census.complete_clusters(60, 5), 1);
    const std::vector<Pose> poses = shell({Quat{1, 0, 0, 0}, {20, 20, 20}});
    const double direct = direct_energy(c, sites_at(c, poses));
    EXPECT_NEAR(direct, -1219.15, 0.005);  // the note's shell energy at e = 0.09
    EXPECT_NEAR(engine_energy(c, poses, kE), direct, 1e-9 * std::fabs(direct));
    std::printf("PH: %zu spheres, closest non-bonded partner %.3f, shell energy %.2f at e = %.2f\n",
                c.spheres.size(), closest_other, direct, kE);
}

namespace {

/// The spheres-and-sites term without its ranges by species (ForceTerm::pair_ranges): the
/// neighbour list then keeps every pair within the cutoff, as before ranges by species.
class WholeRange final : public ForceTerm {
public:
    explicit WholeRange(std::unique_ptr<ForceTerm> term) : term_(std::move(term)) {}
    std::string name() const override { return term_->name(); }
    double cutoff() const override { return term_->cutoff(); }
    bool conservative() const override { return term_->conservative(); }
    unsigned ghost_fields() const override { return term_->ghost_fields(); }
    unsigned particle_fields() const override { return term_->particle_fields(); }
    void add_forces(ParticleStore& s, const NeighbourList& list, const ForceContext& c, bool sample,
                    ForceSums& sums) const override {
        term_->add_forces(s, list, c, sample, sums);
    }
    bool honours_range() const override { return term_->honours_range(); }
    bool on_backend() const override { return term_->on_backend(); }
    void add_forces_on_backend(const BackendParticles& p, const ForceContext& c, bool sample,
                               ForceSums& sums) const override {
        term_->add_forces_on_backend(p, c, sample, sums);
    }

private:
    std::unique_ptr<ForceTerm> term_;
};

/// A closed shell at e = 0.09 and four monomers in a solvent of free volume spheres, after
/// `steps` steps on `backend` with `layout`: every position by id, and the rebuilds.
std::pair<std::map<std::int64_t, Vec3>, long long> shell_in_solvent(bool by_species, Backend backend,
                                                                    ListLayout layout, int steps) {
    const Capsomer c = pw_capsomer();
    RunSettings rs;
    rs.backend = backend;
    rs.list_layout = layout;
    Simulation sim(MPI_COMM_WORLD, rs);
    sim.set_box(big_box());
    std::vector<double> masses{1.0};
    masses.resize(kFirstSite + c.sites.size(), 0.0);
    sim.set_species_masses(masses);
    std::unique_ptr<ForceTerm> term = make_soft_spheres_and_sites(attraction(c, kE));
    sim.add_force(by_species ? std::move(term) : std::make_unique<WholeRange>(std::move(term)));
    std::vector<Pose> poses = shell({Quat{1, 0, 0, 0}, {20, 20, 20}});
    for (int m = 0; m < 4; ++m) poses.push_back({Quat{1, 0, 0, 0}, Vec3{6.0 + 28.0 * (m % 2), 6.0 + 28.0 * (m / 2), 6.0}});
    std::vector<Vec3> velocity;
    for (std::size_t b = 0; b < poses.size(); ++b)
        velocity.push_back(0.2 * Vec3{gaussian(3, b, 0), gaussian(3, b, 1), gaussian(3, b, 2)});
    std::int64_t id = add_capsomers(sim, c, poses, velocity);
    // Solvent on a lattice of spacing 2, clear of the shell (outer radius < 7) and the monomers.
    for (int i = 0; i < 20; ++i)
        for (int j = 0; j < 20; ++j)
            for (int k = 0; k < 20; ++k) {
                const Vec3 p{1.0 + 2 * i, 1.0 + 2 * j, 1.0 + 2 * k};
                bool clear = norm(p - Vec3{20, 20, 20}) > 9;
                for (std::size_t b = 60; b < poses.size(); ++b) clear = clear && norm(p - poses[b].shift) > 5;
                if (!clear) continue;
                sim.add_particle(p, {gaussian(5, id, 0), gaussian(5, id, 1), gaussian(5, id, 2)}, 0, id);
                ++id;
            }
    sim.initialise();
    for (int s = 0; s < steps; ++s) sim.step(s + 1 == steps);
    std::map<std::int64_t, Vec3> at;
    const ParticleStore& p = sim.particles();
    for (std::size_t i = 0; i < p.n_owned(); ++i) at[p.id[i]] = p.position[i];
    return {at, sim.rebuilds()};
}

}  // namespace

TEST(Capsomer, ListBySpeciesRangeChangesNoBit) {
    // A pair the list leaves out by its species' range (solvent beyond the WCA range, a sphere
    // and a site, sites that are not partners) adds an exact zero to every force: the run is
    // the same, bit for bit, as with every pair listed to the attraction's range, on the host's
    // half list and on the back end's full list (the checking back end runs its loops).
    for (const auto& [backend, layout] : {std::pair{Backend::Host, ListLayout::Half},
                                          std::pair{Backend::Checking, ListLayout::Full}}) {
        const auto [whole, whole_rebuilds] = shell_in_solvent(false, backend, layout, 300);
        const auto [short_, short_rebuilds] = shell_in_solvent(true, backend, layout, 300);
        EXPECT_GE(whole_rebuilds, 5);  // several lists built on the way
        EXPECT_EQ(short_rebuilds, whole_rebuilds);
        ASSERT_EQ(short_.size(), whole.size());
        int differ = 0;
        for (const auto& [id, x] : whole) {
            const Vec3& y = short_.at(id);
            differ += (x.x != y.x || x.y != y.y || x.z != y.z) ? 1 : 0;
        }
        EXPECT_EQ(differ, 0) << "of " << whole.size() << " particles";
    }
}

TEST(CapsomerCages, RotationGroups) {
    // Orders 12, 24, 60, each closed under products, with the ring's rotation about the cage
    // vertex and 120 deg about the face centre; the 60 are the shell's group, in its order.
    for (const int members : {12, 24, 60}) {
        const std::vector<Quat> g = cage_rotations(members);
        ASSERT_EQ(int(g.size()), members);
        for (const Quat& q : g)
            for (const Quat& r : g) {
                int found = 0;
                for (const Quat& s : g) found += std::fabs(std::fabs(dot(q * r, s)) - 1) < 1e-12;
                ASSERT_EQ(found, 1) << members;
            }
    }
    const std::vector<Quat> shell = icosahedral_rotations(), same = cage_rotations(60);
    for (std::size_t k = 0; k < 60; ++k) EXPECT_NEAR(std::fabs(dot(shell[k], same[k])), 1, 1e-12);
    EXPECT_THROW(cage_rotations(30), std::invalid_argument);
}

TEST(CapsomerCages, PwCagesAgainstAnIndependentFit) {
    // The lowest cages of 60, 24 and 12 PW capsomers against scripts/capsid_polymorphs (Python:
    // the note's tables, scipy's Powell from six starts; benchmarks/logs/capsid_polymorphs_
    // 2026-12-04.log), which gives -21.2689, -19.3189, -12.6265 per capsomer at centre radii
    // 4.1728, 2.6372, 1.9860 and 5, 5, 2 bonds. Both minimise to 1e-7 or better in the pose;
    // the energies agree to the printed 4 decimals, so 2e-4 allows the last digit's rounding
    // and either minimiser stopping 1e-4 short.
    const Capsomer c = pw_capsomer();
    SiteAttraction s;
    s.partner = c.partner;
    s.epsilon = kE;
    const Cage shell = closed_cage(c, 60, s), octahedral = closed_cage(c, 24, s), tetrahedral = closed_cage(c, 12, s);
    EXPECT_NEAR(shell.energy, -21.2689, 2e-4);
    EXPECT_NEAR(octahedral.energy, -19.3189, 2e-4);
    EXPECT_NEAR(tetrahedral.energy, -12.6265, 2e-4);
    EXPECT_NEAR(shell.centre_radius, 4.1728, 2e-3);
    EXPECT_NEAR(octahedral.centre_radius, 2.6372, 2e-3);
    EXPECT_NEAR(tetrahedral.centre_radius, 1.9860, 2e-3);
    EXPECT_EQ(shell.bonds, 5);
    EXPECT_EQ(octahedral.bonds, 5);
    EXPECT_EQ(tetrahedral.bonds, 2);
    // The shell relaxed from the note's exact shell (-1272.56 / 60 = -21.2093 at centre radius
    // |c| = 4.2157): the tails pull it a little inwards, so lower, but by little.
    EXPECT_LT(shell.energy, -21.2093);
    EXPECT_GT(shell.energy, -21.2093 - 0.1);
    // The long implicit runs' closed clusters of 24 (every member with 5 bonds) have their
    // centres on spheres of radius 2.627-2.653 (scripts/capsid_cages, capsid_assembly_long_
    // cages_2026-12-04.log): the octahedral cage, at finite temperature, within its spread.
    EXPECT_NEAR(octahedral.centre_radius, 2.64, 0.02);
}

TEST(CapsomerCages, SiteRowsFartherApartMakeTheCageCostMore) {
    // scripts/capsid_polymorphs 0 1.2 (the same log): rows at 0 and 1.2 put the 24-cage 4.88
    // per capsomer above the shell instead of 1.95; the shell itself is as bound (-21.12).
    SiteDepths wide;
    wide.outer = 0;
    const Capsomer c = pw_capsomer(2.1, wide);
    SiteAttraction s;
    s.partner = c.partner;
    s.epsilon = kE;
    const Cage shell = closed_cage(c, 60, s), octahedral = closed_cage(c, 24, s);
    EXPECT_NEAR(shell.energy, -21.1244, 2e-4);
    EXPECT_NEAR(octahedral.energy - shell.energy, 4.8815, 4e-4);
    EXPECT_EQ(c.site_depths.outer, 0);
    EXPECT_THROW(pw_capsomer(2.1, SiteDepths{1.2, 0.5}), std::invalid_argument);
    EXPECT_THROW(ph_capsomer(3.6, SiteDepths{-0.1, 1.2}), std::invalid_argument);
}

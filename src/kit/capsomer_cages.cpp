// SPDX-License-Identifier: MIT
// Closed cages other than the shell that a capsomer design admits: the lowest-energy cage of
// each symmetry, found by simplex descent over one capsomer's rigid pose.
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "emergent/kit/capsomer.hpp"
#include "force/site_attraction.hpp"

namespace emergent {

namespace {

constexpr int kFirstSite = 1;

double norm(const Vec3& v) { return std::sqrt(dot(v, v)); }
Vec3 unit(const Vec3& v) { return (1 / norm(v)) * v; }

/// The rotation taking unit u to unit v by the shortest arc.
Quat arc(const Vec3& u, const Vec3& v) {
    const Vec3 axis = cross(u, v);
    const double s = norm(axis);
    if (s < 1e-12) return Quat{1, 0, 0, 0};
    return axis_angle(axis, std::atan2(s, dot(u, v)));
}

/// A pose: rotation vector applied after the start rotation, then the offset.
using Pose = std::array<double, 6>;

class CageEnergy {
public:
    CageEnergy(const Capsomer& d, int members, const SiteAttraction& s) : d_(d), group_(cage_rotations(members)) {
        if (d.sites.size() > std::size_t(force::SphereSiteLaw::kMaxSiteTypes))
            throw std::invalid_argument("closed_cage: too many site types");
        SiteAttraction own = s;  // species 0: the spheres; 1 + k: site type k
        own.first_site = kFirstSite;
        own.partner = d.partner;
        law_ = force::sphere_site_law(own);
        for (const Vec3& x : d.spheres) centre_ += x;
        centre_ *= 1.0 / double(d.spheres.size());
        // Start: the shell's 3-fold direction onto the cage's, then about it so that the 5-fold
        // corner's direction comes nearest the cage's ring vertex; shrunk to the cage's size.
        const CageFrame shell = cage_frame(60), cage = cage_frame(members);
        const Vec3 s3 = unit(shell.a + shell.b + shell.c), c3 = unit(cage.a + cage.b + cage.c);
        const Quat first = arc(s3, c3);
        const Vec3 sa = rotate(first, unit(shell.a)), ca = unit(cage.a);
        const Vec3 pa = unit(sa - dot(sa, c3) * c3), pc = unit(ca - dot(ca, c3) * c3);
        start_ = normalized(arc(pa, pc) * first);
        const Vec3 turned = rotate(start_, centre_);
        start_offset_ = (std::sqrt(members / 60.0) - 1) * turned;
    }

    Quat orientation(const Pose& p) const {
        const Vec3 w{p[0], p[1], p[2]};
        const double angle = norm(w);
        const Quat turn = angle > 0 ? axis_angle(w, angle) : Quat{1, 0, 0, 0};
        return normalized(turn * start_);
    }
    Vec3 offset(const Pose& p) const { return start_offset_ + Vec3{p[3], p[4], p[5]}; }

    /// Capsomer 0's spheres and sites in the pose.
    void place(const Pose& p, std::vector<Vec3>& spheres, std::vector<Vec3>& sites) const {
        const Quat q = orientation(p);
        const Vec3 t = offset(p);
        spheres.clear(), sites.clear();
        for (const Vec3& x : d_.spheres) spheres.push_back(rotate(q, x) + t);
        for (const Vec3& x : d_.sites) sites.push_back(rotate(q, x) + t);
    }

    /// Energy per capsomer: half the sum of capsomer 0's pair energies with every other one.
    double operator()(const Pose& p, double* repulsion = nullptr) const {
        std::vector<Vec3> s0, a0;
        place(p, s0, a0);
        double attraction = 0, wca = 0;
        for (std::size_t g = 1; g < group_.size(); ++g) {
            for (std::size_t a = 0; a < a0.size(); ++a) {
                const Vec3 other = rotate(group_[g], a0[std::size_t(d_.partner[a])]);
                Real u = 0;
                const Vec3 r = a0[a] - other;
                law_.force_over_r(force::SphereSiteLaw::kAttraction, dot(r, r), &u);
                attraction += u;
            }
            for (const Vec3& x : s0)
                for (const Vec3& y : s0) {
                    Real u = 0;
                    const Vec3 r = x - rotate(group_[g], y);
                    law_.force_over_r(force::SphereSiteLaw::kRepulsion, dot(r, r), &u);
                    wca += u;
                }
        }
        if (repulsion) *repulsion = 0.5 * wca;
        return 0.5 * (attraction + wca);
    }

    const std::vector<Quat>& group() const { return group_; }
    Vec3 centre() const { return centre_; }

private:
    const Capsomer& d_;
    std::vector<Quat> group_;
    force::SphereSiteLaw law_;
    Vec3 centre_{0, 0, 0};
    Quat start_{1, 0, 0, 0};
    Vec3 start_offset_{0, 0, 0};
};

/// Nelder-Mead simplex descent from x with initial steps `step`: returns the best vertex.
template <class F>
Pose simplex_descent(const F& f, Pose x, double step, double& value) {
    std::array<Pose, 7> v;
    std::array<double, 7> fv;
    for (int i = 0; i < 7; ++i) {
        v[std::size_t(i)] = x;
        if (i > 0) v[std::size_t(i)][std::size_t(i - 1)] += step;
        fv[std::size_t(i)] = f(v[std::size_t(i)]);
    }
    for (int iteration = 0; iteration < 20000; ++iteration) {
        std::array<int, 7> order{0, 1, 2, 3, 4, 5, 6};
        std::sort(order.begin(), order.end(), [&](int a, int b) { return fv[std::size_t(a)] < fv[std::size_t(b)]; });
        const std::size_t best = std::size_t(order[0]), worst = std::size_t(order[6]), second = std::size_t(order[5]);
        if (fv[worst] - fv[best] < 1e-12 * (1 + std::fabs(fv[best]))) break;
        Pose mid{};
        for (int i = 0; i < 6; ++i)
            for (int k = 0; k < 6; ++k) mid[std::size_t(k)] += v[std::size_t(order[std::size_t(i)])][std::size_t(k)] / 6;
        auto along = [&](double t) {
            Pose y;
            for (int k = 0; k < 6; ++k) y[std::size_t(k)] = mid[std::size_t(k)] + t * (v[worst][std::size_t(k)] - mid[std::size_t(k)]);
            return y;
        };
        const Pose reflected = along(-1);
        const double fr = f(reflected);
        if (fr < fv[best]) {
            const Pose expanded = along(-2);
            const double fe = f(expanded);
            if (fe < fr) v[worst] = expanded, fv[worst] = fe;
            else v[worst] = reflected, fv[worst] = fr;
        } else if (fr < fv[second]) {
            v[worst] = reflected, fv[worst] = fr;
        } else {
            const Pose contracted = fr < fv[worst] ? along(-0.5) : along(0.5);
            const double fc = f(contracted);
            if (fc < std::min(fr, fv[worst])) {
                v[worst] = contracted, fv[worst] = fc;
            } else {  // shrink towards the best vertex
                for (std::size_t i = 0; i < 7; ++i) {
                    if (i == best) continue;
                    for (std::size_t k = 0; k < 6; ++k) v[i][k] = v[best][k] + 0.5 * (v[i][k] - v[best][k]);
                    fv[i] = f(v[i]);
                }
            }
        }
    }
    const std::size_t best = std::size_t(std::min_element(fv.begin(), fv.end()) - fv.begin());
    value = fv[best];
    return v[best];
}

}  // namespace

Cage closed_cage(const Capsomer& d, int members, const SiteAttraction& sites, double bond_range) {
    const CageEnergy energy(d, members, sites);
    auto f = [&](const Pose& p) { return energy(p); };
    // Restart from the best pose until a fresh simplex no longer lowers the energy: a simplex
    // can stall on the flat directions before it has found the bottom. One start, the mapped
    // shell pose: four more, turned and shifted, found the same minima for PW and PH at rows
    // (0.5, 1.2) and (0, 1.2), at 5x the time.
    Pose best{};
    double value = f(best);
    for (double step : {0.2, 0.1, 0.05, 0.05, 0.02, 0.02, 0.01}) {
        double v = 0;
        const Pose p = simplex_descent(f, best, step, v);
        if (v < value) value = v, best = p;
    }
    Cage c;
    c.members = members;
    c.energy = energy(best, &c.repulsion);
    c.orientation = energy.orientation(best);
    c.offset = energy.offset(best);
    c.centre_radius = norm(rotate(c.orientation, energy.centre()) + c.offset);
    std::vector<Vec3> s0, a0;
    energy.place(best, s0, a0);
    for (std::size_t g = 1; g < energy.group().size(); ++g)
        for (const std::vector<int>& face : d.faces) {
            double widest = 0;
            for (const int a : face)
                widest = std::max(widest, norm(a0[std::size_t(a)] -
                                               rotate(energy.group()[g], a0[std::size_t(d.partner[std::size_t(a)])])));
            if (widest < bond_range) ++c.bonds, c.widest_bond = std::max(c.widest_bond, widest);
        }
    return c;
}

}  // namespace emergent

// SPDX-License-Identifier: MIT
// The rough rotating end cap as a force term.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "emergent/error.hpp"
#include "force/dispatch.hpp"
#include "force/rough_end_cap.hpp"
#include "neighbour/neighbour_list.hpp"

namespace emergent {

namespace {

struct RoughCapLoop {
    ParticleStore& s;
    std::size_t n_owned;
    const force::RoughCapLattice& lattice;
    const GranularPair& p;
    double range, d_cap, time;
    bool sample;
    ForceSums& sums;
    template <bool Damping, bool Friction>
    void operator()() const {
        force::ContactTally tally;
        for (std::size_t i = 0; i < n_owned; ++i)
            s.force[i] += force::rough_cap_force<Damping, Friction>(
                lattice, p, range, d_cap, s.position[i], s.velocity[i], s.diameter[i], time,
                sample ? &tally : nullptr);
        if (!sample) return;
        sums.potential += tally.energy;
        sums.max_overlap = std::max(sums.max_overlap, tally.max_overlap);
    }
};

class RoughEndCapTerm final : public ForceTerm {
public:
    RoughEndCapTerm(const RoughEndCap& c, const GranularPair& p, double range)
        : cap_(c), lattice_(force::rough_cap_lattice(c)), p_(p), range_(range) {}
    std::string name() const override { return "rough-end-cap"; }
    bool conservative() const override {
        return p_.gamma_n == 0 && (p_.gamma_s == 0 || p_.mu == 0) && cap_.omega == 0;
    }
    double cutoff() const override { return 0; }
    void add_forces(ParticleStore& s, const NeighbourList& list, const ForceContext& c,
                    bool sample, ForceSums& sums) const override {
        const bool damping = p_.gamma_n != 0, friction = p_.gamma_s != 0 && p_.mu != 0;
        force::dispatch_bools(RoughCapLoop{s, list.n_owned(), lattice_, p_, range_,
                                           cap_.sphere_diameter, c.time, sample, sums},
                              damping, friction);
    }

private:
    RoughEndCap cap_;
    force::RoughCapLattice lattice_;
    GranularPair p_;
    double range_;
};

}  // namespace

std::unique_ptr<ForceTerm> make_rough_end_cap(const RoughEndCap& c, const GranularPair& p,
                                              double range_factor) {
    std::ostringstream msg;
    if (!(c.spacing > 0) || !(c.sphere_diameter > 0) || !(range_factor > 0) || !(c.radius > 0))
        msg << "rough end cap: radius=" << c.radius << ", spacing=" << c.spacing
            << ", sphere_diameter=" << c.sphere_diameter << " and range factor " << range_factor
            << " must be > 0";
    else if (!std::isfinite(c.omega) || !std::isfinite(c.z))
        msg << "rough end cap: z=" << c.z << " and omega=" << c.omega << " must be finite";
    else if (!(p.k_n > 0) || p.gamma_n < 0 || p.gamma_s < 0 || p.mu < 0)
        msg << "rough end cap: k_n=" << p.k_n << " must be > 0 and gamma_n, gamma_s, mu >= 0";
    if (!msg.str().empty()) throw InputError(msg.str());
    return std::make_unique<RoughEndCapTerm>(c, p, range_factor);
}

std::vector<Vec3> rough_end_cap_spheres(const RoughEndCap& c, double time) {
    const force::RoughCapLattice l = force::rough_cap_lattice(c);
    std::vector<Vec3> out;
    const int nj = static_cast<int>(std::ceil(c.radius / l.row_spacing)) + 1;
    const int ni = static_cast<int>(std::ceil(c.radius / l.spacing)) + 1;
    for (int j = -nj; j <= nj; ++j)
        for (int i = -ni; i <= ni; ++i)
            if (l.has(i, j)) out.push_back(l.sphere(i, j, time));
    return out;
}

}  // namespace emergent

// SPDX-License-Identifier: MIT
// The rough rotating cylinder wall as a force term.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "emergent/error.hpp"
#include "force/dispatch.hpp"
#include "force/rough_cylinder.hpp"
#include "neighbour/neighbour_list.hpp"

namespace emergent {

namespace {

struct RoughCylinderLoop {
    ParticleStore& s;
    std::size_t n_owned;
    const force::RoughCylinderLattice& lattice;
    const GranularPair& p;
    double range, d_wall, time;
    bool sample;
    ForceSums& sums;
    template <bool Damping, bool Friction>
    void operator()() const {
        force::ContactTally tally;
        for (std::size_t i = 0; i < n_owned; ++i)
            s.force[i] += force::rough_cylinder_force<Damping, Friction>(
                lattice, p, range, d_wall, s.position[i], s.velocity[i], s.diameter[i], time,
                sample ? &tally : nullptr);
        if (!sample) return;
        sums.potential += tally.energy;
        sums.max_overlap = std::max(sums.max_overlap, tally.max_overlap);
    }
};

class RoughCylinderWall final : public ForceTerm {
public:
    RoughCylinderWall(const RoughCylinder& w, const GranularPair& p, double range)
        : wall_(w), lattice_(force::rough_cylinder_lattice(w)), p_(p), range_(range) {}
    std::string name() const override { return "rough-cylinder-wall"; }
    bool conservative() const override {
        return p_.gamma_n == 0 && (p_.gamma_s == 0 || p_.mu == 0) && wall_.omega == 0;
    }
    double cutoff() const override { return 0; }
    void add_forces(ParticleStore& s, const NeighbourList& list, const ForceContext& c,
                    bool sample, ForceSums& sums) const override {
        const bool damping = p_.gamma_n != 0, friction = p_.gamma_s != 0 && p_.mu != 0;
        force::dispatch_bools(RoughCylinderLoop{s, list.n_owned(), lattice_, p_, range_,
                                                wall_.sphere_diameter, c.time, sample, sums},
                              damping, friction);
    }

private:
    RoughCylinder wall_;
    force::RoughCylinderLattice lattice_;
    GranularPair p_;
    double range_;
};

}  // namespace

std::unique_ptr<ForceTerm> make_rough_cylinder_wall(const RoughCylinder& w,
                                                    const GranularPair& p, double range_factor) {
    std::ostringstream msg;
    if (!(w.spacing > 0) || !(w.sphere_diameter > 0) || !(range_factor > 0))
        msg << "rough cylinder wall: spacing=" << w.spacing << ", sphere_diameter="
            << w.sphere_diameter << " and range factor " << range_factor << " must be > 0";
    else if (!(w.z_hi > w.z_lo))
        msg << "rough cylinder wall: z_hi=" << w.z_hi << " must exceed z_lo=" << w.z_lo;
    // The candidate window around a particle (four spheres per ring) must not wrap onto itself.
    else if (!(w.radius >= 1.2 * w.spacing))
        msg << "rough cylinder wall: radius=" << w.radius << " must be at least 1.2 spacing ("
            << 1.2 * w.spacing << ")";
    else if (!std::isfinite(w.omega))
        msg << "rough cylinder wall: omega=" << w.omega << " is not finite";
    else if (!(p.k_n > 0) || p.gamma_n < 0 || p.gamma_s < 0 || p.mu < 0)
        msg << "rough cylinder wall: k_n=" << p.k_n << " must be > 0 and gamma_n, gamma_s, mu >= 0";
    if (!msg.str().empty()) throw InputError(msg.str());
    return std::make_unique<RoughCylinderWall>(w, p, range_factor);
}

std::vector<Vec3> rough_cylinder_spheres(const RoughCylinder& w, double time) {
    const force::RoughCylinderLattice l = force::rough_cylinder_lattice(w);
    std::vector<Vec3> out;
    out.reserve(static_cast<std::size_t>(l.n_rows) * l.n_around);
    for (int k = 0; k < l.n_rows; ++k)
        for (int j = 0; j < l.n_around; ++j) out.push_back(l.sphere(k, j, time));
    return out;
}

}  // namespace emergent

// SPDX-License-Identifier: MIT
// Walls made rough by embedded spheres on a grid that turns with them (the drum's curved wall
// and its optional rough end caps), as force terms: one term for any such grid.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "emergent/error.hpp"
#include "force/dispatch.hpp"
#include "force/per_particle_term.hpp"
#include "force/rough_cylinder.hpp"
#include "force/rough_end_cap.hpp"
#include "neighbour/neighbour_list.hpp"

namespace emergent {

namespace {

/// force::rough_wall_force of one grid (Lattice) on one particle (force::TalliedWallForce
/// applies it to each).
template <class Lattice, bool Damping, bool Friction>
struct RoughWallLaw {
    Lattice lattice;
    GranularPair p;
    Real range, d_wall, time;
    EMERGENT_HD Vec3 operator()(const Vec3& x, const Vec3& v, Real d, force::ContactTally* tally) const {
        return force::rough_wall_force<Damping, Friction>(lattice, p, range, d_wall, x, v, d, time, tally);
    }
};

/// Applies force::rough_wall_force of one grid (Lattice) to every owned sphere: one loop for
/// the host's store and the back end's arrays.
template <class Lattice>
class RoughWall final : public force::PerParticleWall {
public:
    RoughWall(std::string name, const Lattice& lattice, const GranularPair& p, double range,
              double d_wall)
        : name_(std::move(name)), lattice_(lattice), p_(p), range_(range), d_wall_(d_wall) {}
    std::string name() const override { return name_; }
    bool conservative() const override {
        return p_.gamma_n == 0 && (p_.gamma_s == 0 || p_.mu == 0) && lattice_.omega == 0;
    }

private:
    struct Loop {
        const RoughWall& w;
        const BackendParticles& p;
        double time;
        ForceSums& sums;
        template <bool Sample, bool Damping, bool Friction>
        void operator()() const {
            launch_law<Sample>(p, RoughWallLaw<Lattice, Damping, Friction>{w.lattice_, w.p_, w.range_, w.d_wall_, time},
                               sums);
        }
    };
    void add(const BackendParticles& p, double time, bool sample, ForceSums& sums) const override {
        const bool damping = p_.gamma_n != 0, friction = p_.gamma_s != 0 && p_.mu != 0;
        force::dispatch_bools(Loop{*this, p, time, sums}, sample, damping, friction);
    }

    std::string name_;
    Lattice lattice_;
    GranularPair p_;
    double range_, d_wall_;
};

/// Wall spheres closer than a quarter of their diameter make no roughness a particle could
/// feel, only a wall that touches it dozens of times over (as stiff as that many contacts), and
/// the spheres within reach of one particle grow as (diameter / spacing)^2: at 1e-5 a step
/// takes hours.
constexpr double kMinSpacingPerDiameter = 0.25;

void check_sizes(const std::string& what, double spacing, double sphere_diameter, double range) {
    std::ostringstream msg;
    if (!(spacing > 0 && sphere_diameter > 0 && range > 0))
        msg << what << ": spacing=" << spacing << ", sphere_diameter=" << sphere_diameter
            << " and range factor " << range << " must be > 0";
    else if (!(spacing >= kMinSpacingPerDiameter * sphere_diameter))
        msg << what << ": spacing=" << spacing << " must be at least " << kMinSpacingPerDiameter
            << " sphere_diameter (" << kMinSpacingPerDiameter * sphere_diameter
            << "): closer spheres overlap into a wall that touches a particle many times over";
    else
        return;
    throw InputError(msg.str());
}

}  // namespace

std::unique_ptr<ForceTerm> make_rough_cylinder_wall(const RoughCylinder& w,
                                                    const GranularPair& p, double range_factor) {
    const std::string what = "rough cylinder wall";
    check_sizes(what, w.spacing, w.sphere_diameter, range_factor);
    std::ostringstream msg;
    if (!(w.z_hi > w.z_lo))
        msg << what << ": z_hi=" << w.z_hi << " must exceed z_lo=" << w.z_lo;
    // The candidate window around a particle (four spheres per ring) must not wrap onto itself.
    else if (!(w.radius >= 1.2 * w.spacing))
        msg << what << ": radius=" << w.radius << " must be at least 1.2 spacing ("
            << 1.2 * w.spacing << ")";
    else if (!std::isfinite(w.omega))
        msg << what << ": omega=" << w.omega << " is not finite";
    if (!msg.str().empty()) throw InputError(msg.str());
    force::check_granular_pair(p, what);
    return std::make_unique<RoughWall<force::RoughCylinderLattice>>(
        "rough-cylinder-wall", force::rough_cylinder_lattice(w), p, range_factor, w.sphere_diameter);
}

std::unique_ptr<ForceTerm> make_rough_end_cap(const RoughEndCap& c, const GranularPair& p,
                                              double range_factor) {
    const std::string what = "rough end cap";
    check_sizes(what, c.spacing, c.sphere_diameter, range_factor);
    if (!(c.radius > 0) || !std::isfinite(c.omega) || !std::isfinite(c.z)) {
        std::ostringstream msg;
        msg << what << ": radius=" << c.radius << " must be > 0, z=" << c.z << " and omega="
            << c.omega << " finite";
        throw InputError(msg.str());
    }
    force::check_granular_pair(p, what);
    return std::make_unique<RoughWall<force::RoughCapLattice>>(
        "rough-end-cap", force::rough_cap_lattice(c), p, range_factor, c.sphere_diameter);
}

std::vector<Vec3> rough_cylinder_spheres(const RoughCylinder& w, double time) {
    const force::RoughCylinderLattice l = force::rough_cylinder_lattice(w);
    std::vector<Vec3> out;
    out.reserve(static_cast<std::size_t>(l.n_rows) * l.n_around);
    for (int k = 0; k < l.n_rows; ++k)
        for (int j = 0; j < l.n_around; ++j) out.push_back(l.sphere(k, j, time));
    return out;
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

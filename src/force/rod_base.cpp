// SPDX-License-Identifier: MIT
// The vibrating rod base and the smooth cylindrical wall as force terms: one per-particle loop
// (force/rod_base.hpp) for the host's store and the back end's arrays alike.
#include "force/rod_base.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "emergent/error.hpp"
#include "force/dispatch.hpp"
#include "force/per_particle_term.hpp"
#include "neighbour/neighbour_list.hpp"

namespace emergent {

namespace {

constexpr double kTwoPi = 6.283185307179586;

class RodBaseTerm final : public force::PerParticleWall {
public:
    RodBaseTerm(const force::RodLattice& lattice, const GranularPair& p, double range, double d_rod)
        : lattice_(lattice), p_(p), range_(range), d_rod_(d_rod) {}
    std::string name() const override { return "rod-base"; }
    bool conservative() const override { return p_.gamma_n == 0 && lattice_.amplitude == 0; }

private:
    struct Loop {
        const RodBaseTerm& t;
        const BackendParticles& p;
        double time;
        ForceSums& sums;
        template <bool Sample, bool Damping>
        void operator()() const {
            launch_law<Sample>(p, force::RodBaseLaw<Damping>{t.lattice_, t.p_, t.range_, t.d_rod_, time}, sums);
        }
    };
    void add(const BackendParticles& p, double time, bool sample, ForceSums& sums) const override {
        force::dispatch_bools(Loop{*this, p, time, sums}, sample, p_.gamma_n != 0);
    }

    force::RodLattice lattice_;
    GranularPair p_;
    double range_, d_rod_;
};

class CylinderWallTerm final : public force::PerParticleWall {
public:
    CylinderWallTerm(double radius, const GranularPair& p, double range)
        : radius_(radius), p_(p), range_(range) {}
    std::string name() const override { return "cylinder-wall"; }
    bool conservative() const override { return p_.gamma_n == 0; }

private:
    struct Loop {
        const CylinderWallTerm& t;
        const BackendParticles& p;
        ForceSums& sums;
        template <bool Sample, bool Damping>
        void operator()() const {
            launch<Sample>(p, force::CylinderWallForce<Sample, Damping>{p.position, p.velocity, p.diameter,
                                                                        p.force, t.radius_, t.range_, t.p_,
                                                                        p.energy, p.overlap},
                           sums);
        }
    };
    void add(const BackendParticles& p, double, bool sample, ForceSums& sums) const override {
        force::dispatch_bools(Loop{*this, p, sums}, sample, p_.gamma_n != 0);
    }

    double radius_;
    GranularPair p_;
    double range_;
};

}  // namespace

force::RodLattice force::rod_lattice(const RodBase& b) {
    const std::string what = "rod base";
    std::ostringstream msg;
    const auto& v = b.vertices;
    if (v.size() < 2 || v.size() > force::kRodBaseMaxEdges + 1)
        msg << what << ": the profile needs 2 to " << force::kRodBaseMaxEdges + 1 << " vertices, has "
            << v.size();
    else if (!(b.period > 0) || !std::isfinite(b.period))
        msg << what << ": period=" << b.period << " must be > 0";
    else if (v.front().first != 0 || std::fabs(v.back().first - b.period) > 1e-9 * b.period ||
             std::fabs(v.back().second - v.front().second) > 1e-9 * b.period)
        msg << what << ": the profile must run from u = 0 to u = period=" << b.period
            << " and end at the height it starts";
    else if (!(b.rod_spacing > 0) || !(b.rod_diameter > 0))
        msg << what << ": rod_spacing=" << b.rod_spacing << " and rod_diameter=" << b.rod_diameter
            << " must be > 0";
    // A period shorter than two rod spacings leaves a flank without a rod of its own (at 1e-300
    // the grains fell through), and rods closer than a quarter of their diameter merge into a
    // surface that touches a grain many times over, at a cost that grows as their number.
    else if (!(b.period >= 2 * b.rod_spacing))
        msg << what << ": period=" << b.period << " must be at least 2 rod_spacing (" << 2 * b.rod_spacing
            << "): each flank of a tooth needs its rods";
    else if (!(b.rod_spacing >= 0.25 * b.rod_diameter))
        msg << what << ": rod_spacing=" << b.rod_spacing << " must be at least 0.25 rod_diameter ("
            << 0.25 * b.rod_diameter << "): closer rods merge into a surface touching a grain many times over";
    else if (!(b.amplitude >= 0) || !(b.frequency >= 0) || !std::isfinite(b.amplitude * b.frequency))
        msg << what << ": amplitude=" << b.amplitude << " and frequency=" << b.frequency
            << " must be >= 0";
    else
        for (std::size_t k = 0; k + 1 < v.size(); ++k)
            if (v[k + 1].first < v[k].first) {
                msg << what << ": profile vertex " << k + 1 << " goes back along u (u="
                    << v[k + 1].first << " < " << v[k].first << ")";
                break;
            }
    if (!msg.str().empty()) throw InputError(msg.str());
    force::RodLattice l;
    l.n_edges = static_cast<int>(v.size()) - 1;
    l.period = b.period;
    l.u_lo = b.u_lo;
    l.u_hi = b.u_hi;
    l.rings = b.rings;
    l.backing = b.backing;
    l.amplitude = b.amplitude;
    l.angular_frequency = kTwoPi * b.frequency;
    l.top = v[0].second;
    for (int e = 0; e < l.n_edges; ++e) {
        const double du = v[e + 1].first - v[e].first, dz = v[e + 1].second - v[e].second;
        const double length = std::hypot(du, dz);
        // An edge of zero length (a repeated vertex) holds no rods of its own.
        const int n = length > 0 ? std::max(1, static_cast<int>(std::ceil(length / b.rod_spacing - 1e-9))) : 0;
        l.start_u[e] = v[e].first;
        l.start_z[e] = v[e].second;
        l.step_u[e] = n > 0 ? du / n : 0;
        l.step_z[e] = n > 0 ? dz / n : 0;
        l.count[e] = n;
        l.top = std::max(l.top, v[e + 1].second);
        if (n == 0) l.step_u[e] = 1, l.count[e] = 0;  // never visited; keeps the step nonzero
    }
    return l;
}

std::unique_ptr<ForceTerm> make_rod_base(const RodBase& b, const GranularPair& p, double range_factor) {
    const force::RodLattice l = force::rod_lattice(b);
    force::check_granular_pair(p, "rod base");
    if (!(range_factor > 0)) throw InputError("rod base: range factor must be > 0");
    return std::make_unique<RodBaseTerm>(l, p, range_factor, b.rod_diameter);
}

std::vector<std::pair<double, double>> rod_base_rods(const RodBase& b, double lo, double hi) {
    const force::RodLattice l = force::rod_lattice(b);
    std::vector<std::pair<double, double>> rods;
    const int first = static_cast<int>(std::floor(lo / l.period)) - 1;
    const int last = static_cast<int>(std::floor(hi / l.period)) + 1;
    for (int m = first; m <= last; ++m)
        for (int e = 0; e < l.n_edges; ++e)
            for (int j = 0; j < l.count[e]; ++j) {
                const double u = l.start_u[e] + m * l.period + j * l.step_u[e];
                if (u >= lo && u <= hi && u >= l.u_lo && u <= l.u_hi)
                    rods.emplace_back(u, l.start_z[e] + j * l.step_z[e]);
            }
    return rods;
}

std::unique_ptr<ForceTerm> make_cylinder_wall(double radius, const GranularPair& p, double range_factor) {
    if (!(radius > 0) || !std::isfinite(radius))
        throw InputError("cylinder wall: radius=" + std::to_string(radius) + " must be > 0");
    force::check_granular_pair(p, "cylinder wall");
    return std::make_unique<CylinderWallTerm>(radius, p, range_factor);
}

}  // namespace emergent

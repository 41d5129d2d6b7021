// SPDX-License-Identifier: MIT
// The soft-spheres-and-sites force term (the capsid model's interactions).
#include <cmath>
#include <sstream>

#include "emergent/error.hpp"
#include "emergent/execution.hpp"
#include "emergent/force_term.hpp"
#include "force/site_attraction.hpp"
#include "neighbour/neighbour_list.hpp"

namespace emergent {

namespace {

constexpr double kWcaRange = 1.122462048309373;  // 2^(1/6), sigma = 1

class SpheresAndSitesTerm final : public ForceTerm {
public:
    SpheresAndSitesTerm(const SiteAttraction& s, const force::SphereSiteLaw& law)
        : settings_(s), law_(law) {}

    std::string name() const override { return "spheres-and-sites"; }
    double cutoff() const override { return std::max(settings_.range, kWcaRange); }
    unsigned ghost_fields() const override { return kPosition | kSpecies; }
    /// Volume meets volume within the WCA range, a site its partner within the attraction's;
    /// volume and sites, and sites that are not partners, never meet.
    std::vector<double> pair_ranges() const override {
        const int n = law_.first_site + law_.n_site_types;
        std::vector<double> r(std::size_t(n) * std::size_t(n), 0.0);
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                const int kind = law_.kind(i, j);
                r[std::size_t(i * n + j)] = kind == force::SphereSiteLaw::kRepulsion ? kWcaRange
                                            : kind == force::SphereSiteLaw::kAttraction ? settings_.range
                                                                                        : 0.0;
            }
        return r;
    }

    void add_forces(ParticleStore& s, const NeighbourList& list, const ForceContext& rows, bool sample,
                    ForceSums& sums) const override {
        const force::PairArrays a{s.position.data(), nullptr, nullptr, s.species.data(), s.force.data(),
                                  list.offsets(), list.neighbours()};
        const force::PairSums sum =
            sample ? force::pair_forces_half_list<true>(law_, a, list.n_owned(), rows.first, rows.last)
                   : force::pair_forces_half_list<false>(law_, a, list.n_owned(), rows.first, rows.last);
        sums.potential += sum.energy;
        sums.virial += sum.virial;
    }

    bool on_backend() const override { return true; }
    void add_forces_on_backend(const BackendParticles& p, const ForceContext&, bool sample,
                               ForceSums& sums) const override {
        const force::PairArrays a{p.position, nullptr, nullptr, p.species, p.force, p.list_offset, p.list_index};
        if (!sample) {
            exec::for_each(p.target, p.n_owned, force::PairForcesFullList<force::SphereSiteLaw, false>{law_, a});
            return;
        }
        exec::for_each(p.target, p.n_owned,
                       force::PairForcesFullList<force::SphereSiteLaw, true>{law_, a, p.energy, p.virial});
        sums.potential += exec::transform_sum<double>(p.target, p.n_owned, exec::ElementOf<Real>{p.energy});
        sums.virial += exec::transform_sum<double>(p.target, p.n_owned, exec::ElementOf<Real>{p.virial});
    }

private:
    SiteAttraction settings_;
    force::SphereSiteLaw law_;
};

}  // namespace

std::unique_ptr<ForceTerm> make_soft_spheres_and_sites(const SiteAttraction& s) {
    std::ostringstream msg;
    const int n = static_cast<int>(s.partner.size());
    if (s.first_site < 1) msg << "first_site=" << s.first_site << " must be >= 1 (species 0 has volume)";
    else if (n > force::SphereSiteLaw::kMaxSiteTypes)
        msg << n << " site types: at most " << force::SphereSiteLaw::kMaxSiteTypes;
    else if (!(s.epsilon >= 0)) msg << "attraction=" << s.epsilon << " must be >= 0";
    else if (!(s.harmonic_range > 0) || !(s.range > s.harmonic_range))
        msg << "harmonic_range=" << s.harmonic_range << " and range=" << s.range
            << " must satisfy 0 < harmonic_range < range";
    for (int k = 0; k < n && msg.str().empty(); ++k) {
        const int q = s.partner[std::size_t(k)];
        if (q < 0 || q >= n || s.partner[std::size_t(q)] != k)
            msg << "site type " << k << " has partner " << q << ", not a mutual partner among the "
                << n << " types";
    }
    if (!msg.str().empty()) throw InputError("spheres-and-sites: " + msg.str());
    return std::make_unique<SpheresAndSitesTerm>(s, force::sphere_site_law(s));
}

force::SphereSiteLaw force::sphere_site_law(const SiteAttraction& s) {
    const int n = static_cast<int>(s.partner.size());
    SphereSiteLaw law;
    law.first_site = s.first_site;
    law.n_site_types = n;
    for (int k = 0; k < n; ++k) law.partner[k] = s.partner[std::size_t(k)];
    law.e = s.epsilon;
    law.range_sq = s.range * s.range;
    law.inverse_range_sq = 1 / law.range_sq;
    law.harmonic_sq = s.harmonic_range * s.harmonic_range;
    law.inverse_harmonic_4 = 1 / (law.harmonic_sq * law.harmonic_sq);
    return law;
}

}  // namespace emergent

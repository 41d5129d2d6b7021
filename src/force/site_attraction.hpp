// SPDX-License-Identifier: MIT
// Soft spheres with attraction sites (the capsid model): the pair law, a law of the neighbour
// loop (neighbour_loop.hpp) on the host's half list and the back end's full list alike.
#pragma once

#include <cstddef>
#include <cstdint>

#include "emergent/force_term.hpp"
#include "emergent/vec3.hpp"
#include "emergent/neighbour_loop.hpp"

namespace emergent::force {

/// Which law a pair of species meets: none, WCA between volume species, or the site attraction
/// between partner site types. Held by value (device kernels get a copy).
struct SphereSiteLaw {
    static constexpr int kMaxSiteTypes = 32;
    enum Kind { kNone = 0, kRepulsion = 1, kAttraction = 2 };

    int first_site = 1, n_site_types = 0;
    int partner[kMaxSiteTypes] = {};
    Real wca_cutoff_sq = 1.2599210498948732;  // 2^(1/3): WCA, sigma = epsilon = 1
    Real e = 0, range_sq = 9, harmonic_sq = 0.09, inverse_range_sq = 1.0 / 9, inverse_harmonic_4 = 0;

    EMERGENT_HD int kind(int a, int b) const {
        if (a < first_site && b < first_site) return kRepulsion;
        const int ta = a - first_site, tb = b - first_site;
        if (ta >= 0 && tb >= 0 && ta < n_site_types && partner[ta] == tb) return kAttraction;
        return kNone;
    }

    /// |f|/r of a pair of kind `k` at squared distance r2 (0 beyond its range); with `energy`,
    /// also its energy.
    EMERGENT_HD Real force_over_r(int k, Real r2, Real* energy) const {
        if (k == kRepulsion) {
            if (!(r2 < wca_cutoff_sq)) return 0;
            const Real ri2 = Real(1) / r2, ri6 = ri2 * ri2 * ri2;
            if (energy) *energy = Real(4) * ri6 * (ri6 - Real(1)) + Real(1);  // shifted: 0 at 2^(1/6)
            return Real(48) * ri6 * (ri6 - Real(0.5)) * ri2;
        }
        if (k == kAttraction) {
            if (!(r2 < range_sq)) return 0;
            if (r2 < harmonic_sq) {  // stretched harmonic well: finite where partners coincide
                if (energy)
                    *energy = e * (inverse_range_sq + r2 * inverse_harmonic_4 - Real(2) / harmonic_sq);
                return Real(-2) * e * inverse_harmonic_4;
            }
            if (energy) *energy = e * (inverse_range_sq - Real(1) / r2);
            return Real(-2) * e / (r2 * r2);
        }
        return 0;
    }

    /// |f|/r of species si at separation d from species sj (0 if they do not interact).
    EMERGENT_HD Real between(int si, int sj, const Vec3& d, Real* energy) const {
        const int k = kind(si, sj);
        return k == kNone ? Real(0) : force_over_r(k, dot(d, d), energy);
    }

    // As a law of the neighbour loop: every listed pair, with zero force where they do not
    // meet (as between()).
    static constexpr unsigned needs = kNeedsSpecies;
    template <class List, bool Sample>
    EMERGENT_HD bool pair(const PairMember& i, const PairMember& j, const Vec3& d, PairTerm& t) const {
        Real u = 0;
        const Real fr = between(i.species, j.species, d, Sample ? &u : nullptr);
        t.f = fr * d;
        if constexpr (Sample) {
            t.energy = u;
            t.virial = fr * dot(d, d);
        }
        return true;
    }
};

/// The law of settings already checked (make_soft_spheres_and_sites checks them).
SphereSiteLaw sphere_site_law(const SiteAttraction& s);

}  // namespace emergent::force

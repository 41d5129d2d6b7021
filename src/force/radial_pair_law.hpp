// SPDX-License-Identifier: MIT
// A radial pair potential as a law of the neighbour loop (neighbour_loop.hpp). Its evaluator
// gives, from the squared distance r2, the force over distance and the energy:
//   T cutoff_sq;  EMERGENT_HD T force_over_r(T r2) const;  EMERGENT_HD T energy(T r2) const;
// in its own arithmetic type T (lennard_jones.hpp is one). On the host's half list every listed
// pair is evaluated and masked beyond the cutoff (branch-free); on the full list the pairs
// beyond it are skipped.
#pragma once

#include "force/neighbour_loop.hpp"

namespace emergent::force {

template <class Evaluator>
struct RadialPairLaw {
    static constexpr unsigned needs = 0;
    Evaluator eval;

    template <class List, bool Sample>
    EMERGENT_HD bool pair(const PairMember&, const PairMember&, const Vec3& d, PairTerm& t) const {
        using T = decltype(eval.cutoff_sq);
        const T dx = T(d.x), dy = T(d.y), dz = T(d.z);
        const T r2 = dx * dx + dy * dy + dz * dz;
        T fr, inside = T(1);
        if constexpr (List::kHost) {
            inside = r2 < eval.cutoff_sq ? T(1) : T(0);
            fr = inside * eval.force_over_r(r2);
        } else {
            if (!(r2 < eval.cutoff_sq)) return false;
            fr = eval.force_over_r(r2);
        }
        t.f = {Real(fr * dx), Real(fr * dy), Real(fr * dz)};
        if constexpr (Sample) {
            t.energy = List::kHost ? Real(inside * eval.energy(r2)) : Real(eval.energy(r2));
            t.virial = Real(fr * r2);
        }
        return true;
    }
};

/// The same with an evaluator per species pair (row-major, n_species^2) and pairwise damping
/// -gamma (v_ij . r_ij) r_ij / r^2: every feature of a pair law compiled in, to measure what
/// specialisation saves (benchmarks/specialisation_cost.sh). Host half list only.
template <class Evaluator>
struct TabulatedDampedLaw {
    static constexpr unsigned needs = kNeedsVelocity | kNeedsSpecies;
    const Evaluator* pairs = nullptr;
    int n_species = 1;
    Real gamma = 0;

    template <class List, bool Sample>
    bool pair(const PairMember& i, const PairMember& j, const Vec3& d, PairTerm& t) const {
        static_assert(List::kHost, "the generic law runs on the host's half list");
        const Evaluator& eval = pairs[i.species * n_species + j.species];
        const Real dx = d.x, dy = d.y, dz = d.z;
        const Real r2 = dx * dx + dy * dy + dz * dz;
        const Real inside = r2 < eval.cutoff_sq ? Real(1) : Real(0);
        Real fr = inside * eval.force_over_r(r2);
        const Vec3 dv = i.v - j.v;
        fr -= inside * gamma * (dv.x * dx + dv.y * dy + dv.z * dz) / r2;
        t.f = {fr * dx, fr * dy, fr * dz};
        if constexpr (Sample) {
            t.energy = inside * eval.energy(r2);
            t.virial = fr * r2;
        }
        return true;
    }
};

}  // namespace emergent::force

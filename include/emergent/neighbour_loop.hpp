// SPDX-License-Identifier: MIT
// The one loop over neighbour-list pairs, for every pair law and both kinds of list:
// - the half list (host code): each pair once, Newton's third law on both members, a pair with
//   a ghost counting half its energy and virial (the rank that owns the ghost counts the rest);
// - the full list: a per-particle functor that writes only its own particle, so the same code
//   runs as a CPU loop or as one GPU thread per particle without atomics; each particle holds
//   half of each of its pairs' energy and virial.
// A law is an evaluator in the way of HOOMD-blue's: it states what it reads of the two
// particles (`needs`: velocities, diameters, species) and gives one pair's force on i, and with
// sampling its energy, r.f and overlap. It returns false for a pair that does not interact,
// which the loop then skips; a law may instead return every pair, with zero force beyond its
// range (branch-free: where about half the listed pairs lie beyond the cutoff at random, a
// masked multiply costs less than the mispredicted branch), and may choose per list
// (`HalfList::kHost`: the half list is the host's). A law whose pairs mostly lie beyond its
// range (contacts: the list holds the skin too) may add `in_range(i, j, d)`, which reads only
// positions and diameters: the loop then reads a partner's velocity and species only for the
// pairs in range.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>

#include "emergent/vec3.hpp"

namespace emergent::force {

/// What a law reads of a pair's members besides their positions.
enum PairNeeds : unsigned { kNeedsVelocity = 1u, kNeedsDiameter = 2u, kNeedsSpecies = 4u };

/// One member of a pair as the law sees it: the fields it does not need are left unread.
struct PairMember {
    Vec3 x{0, 0, 0}, v{0, 0, 0};
    Real diameter = 1;
    int species = 0;
};

/// One pair's force on i (j gets its negative), and with sampling its energy, r.f and the overlap
/// (contacts; 0 for laws without one).
struct PairTerm {
    Vec3 f{0, 0, 0};
    Real energy = 0, virial = 0, overlap = 0;
};

/// The particle arrays and the list the loops read (and f, which they write).
struct PairArrays {
    const Vec3* x = nullptr;
    const Vec3* v = nullptr;
    const Real* diameter = nullptr;
    const int* species = nullptr;
    Vec3* f = nullptr;
    const std::uint32_t* offset = nullptr;  ///< i's neighbours at index[offset[i] .. offset[i+1])
    const std::uint32_t* index = nullptr;
};

/// The kinds of list, as the laws see them.
struct HalfList {
    static constexpr bool kHost = true;
};
struct FullList {
    static constexpr bool kHost = false;
};

/// Sums of a row (full list) or of the whole loop (half list).
struct PairSums {
    Real energy = 0, virial = 0, overlap = 0;
};

/// True when `Law` has `in_range(const PairMember&, const PairMember&, const Vec3&)`.
template <class Law, class = void>
struct HasRangeTest : std::false_type {};
template <class Law>
struct HasRangeTest<Law, std::void_t<decltype(std::declval<const Law&>().in_range(
                             std::declval<const PairMember&>(), std::declval<const PairMember&>(),
                             std::declval<const Vec3&>()))>> : std::true_type {};

/// What the range test reads of particle `i`: its position, and its diameter where the law needs it.
template <class Law>
EMERGENT_HD PairMember near_member(const PairArrays& a, std::size_t i) {
    PairMember m;
    m.x = a.x[i];
    if constexpr ((Law::needs & kNeedsDiameter) != 0) m.diameter = a.diameter[i];
    return m;
}

/// The rest of what `Law` reads of particle `i`.
template <class Law>
EMERGENT_HD void complete_member(const PairArrays& a, std::size_t i, PairMember& m) {
    if constexpr ((Law::needs & kNeedsVelocity) != 0) m.v = a.v[i];
    if constexpr ((Law::needs & kNeedsSpecies) != 0) m.species = a.species[i];
}

/// Particle `i` as law `Law` reads it.
template <class Law>
EMERGENT_HD PairMember pair_member(const PairArrays& a, std::size_t i) {
    PairMember m = near_member<Law>(a, i);
    complete_member<Law>(a, i, m);
    return m;
}

/// Row i of the list: its force into fi, its pairs' energy, r.f and largest overlap into `sums`
/// (weighted as the list requires). On the half list each partner takes the opposite force.
template <class List, bool Sample, class Law>
EMERGENT_HD void pair_row(const Law& law, const PairArrays& a, std::size_t i, std::size_t n_owned, Vec3& fi,
                          PairSums& sums) {
    const PairMember mi = pair_member<Law>(a, i);
    for (std::uint32_t k = a.offset[i]; k < a.offset[i + 1]; ++k) {
        const std::uint32_t j = a.index[k];
        PairMember mj;
        if constexpr (HasRangeTest<Law>::value) {
            mj = near_member<Law>(a, j);
            if (!law.in_range(mi, mj, mi.x - mj.x)) continue;
            complete_member<Law>(a, j, mj);
        } else {
            mj = pair_member<Law>(a, j);
        }
        PairTerm t;
        if (!law.template pair<List, Sample>(mi, mj, mi.x - mj.x, t)) continue;
        fi += t.f;
        if constexpr (List::kHost) a.f[j] -= t.f;
        if constexpr (Sample) {
            // Half list: an owned-ghost pair counts half here. Full list: every pair is
            // listed under both members, so the row is halved when it is stored.
            const Real weight = !List::kHost || j < n_owned ? Real(1) : Real(0.5);
            sums.energy += weight * t.energy;
            sums.virial += weight * t.virial;
            sums.overlap = t.overlap > sums.overlap ? t.overlap : sums.overlap;
        }
    }
}

/// The half list's rows [first, last): forces on both members, the loop's sums returned.
template <bool Sample, class Law>
PairSums pair_forces_half_list(const Law& law, const PairArrays& a, std::size_t n_owned, std::size_t first,
                               std::size_t last) {
    PairSums sums;
    last = std::min(last, n_owned);
    for (std::size_t i = first; i < last; ++i) {
        Vec3 fi{0, 0, 0};
        pair_row<HalfList, Sample>(law, a, i, n_owned, fi, sums);
        a.f[i] += fi;
    }
    return sums;
}

/// The full list as a per-particle functor: f[i] = (or +=, `accumulate`) the sum over i's
/// neighbours; with Sample, energy[i] and virial[i] get half of each of its pairs, overlap[i]
/// (where given) the largest.
template <class Law, bool Sample>
struct PairForcesFullList {
    Law law;
    PairArrays a;
    Real* energy = nullptr;
    Real* virial = nullptr;
    Real* overlap = nullptr;
    bool accumulate = true;

    EMERGENT_HD void operator()(std::size_t i) const {
        Vec3 fi{0, 0, 0};
        PairSums s;
        pair_row<FullList, Sample>(law, a, i, 0, fi, s);
        // A row summed from zero and stored gives the bits adding it to a cleared force does
        // (0 + s = s: a sum started at +0 is never -0).
        a.f[i] = accumulate ? a.f[i] + fi : fi;
        if constexpr (Sample) {
            energy[i] = Real(0.5) * s.energy;
            virial[i] = Real(0.5) * s.virial;
            if (overlap) overlap[i] = s.overlap;
        }
    }
};

}  // namespace emergent::force

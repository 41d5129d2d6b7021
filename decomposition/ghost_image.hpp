// SPDX-License-Identifier: MIT
// A ghost's value from its owner's across a boundary: rotated by whole wedge steps, then
// shifted by a box length (positions) or not (velocities). One functor for the host's halo
// refresh and the back end's, so both give the same bits.
#pragma once

#include <cstddef>

#include "emergent/box.hpp"

namespace emergent::decomp {

/// out[k] = rotate(in[index[k]], turns) + shift.
struct GhostImage {
    const Vec3* in;
    const int* index;
    Vec3* out;
    Wedge wedge;
    int turns;
    Vec3 shift;
    EMERGENT_HD void operator()(std::size_t k) const {
        const Vec3 v = turns ? wedge.rotate(in[index[k]], turns) : in[index[k]];
        out[k] = v + shift;
    }
};

/// One swap of a refresh traced back to the owned particles: each ghost k of the swap records
/// the owned particle its copy starts from (`root`) and the sum of the shifts on the way
/// (`shift`), from its source's record where the source is itself a ghost (an earlier swap's).
/// Ghost slot g is particle n_owned + g.
struct GhostRoot {
    const int* index;       ///< the swap's export indices
    std::size_t n_owned;
    std::size_t first;      ///< the swap's first ghost slot
    int* root;
    Vec3* total_shift;
    Vec3 shift;             ///< the swap's own
    EMERGENT_HD void operator()(std::size_t k) const {
        const std::size_t source = static_cast<std::size_t>(index[k]);
        if (source < n_owned) {
            root[first + k] = static_cast<int>(source);
            total_shift[first + k] = shift;
        } else {
            root[first + k] = root[source - n_owned];
            total_shift[first + k] = total_shift[source - n_owned] + shift;
        }
    }
};

/// Every ghost from its owned root in one pass: out[g] = in[root[g]] + shift[g]. The same bits
/// as the swaps one after another where each component is shifted by at most one swap on any
/// ghost's way (BackendHalo checks the plan): x + s + 0 + 0 = x + (s + 0 + 0).
struct GhostFromRoot {
    const Vec3* in;
    const int* root;
    const Vec3* total_shift;
    bool shifted;  ///< positions; velocities add a zero shift, as each swap does for them
    Vec3* out;
    EMERGENT_HD void operator()(std::size_t g) const {
        out[g] = in[root[g]] + (shifted ? total_shift[g] : Vec3{0, 0, 0});
    }
};

}  // namespace emergent::decomp

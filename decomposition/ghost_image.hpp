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

}  // namespace emergent::decomp

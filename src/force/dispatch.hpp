// SPDX-License-Identifier: MIT
// The one place where run-time switches become compile-time features.
#pragma once

#include <type_traits>

namespace emergent::force {

/// Calls f.template operator()<b0, b1, ...>() with the run-time bools turned into template
/// arguments: one instantiation per combination, chosen once per call, never inside loops.
template <bool... Fixed, class F>
void dispatch_bools(F&& f) {
    f.template operator()<Fixed...>();
}

template <bool... Fixed, class F, class... Rest>
void dispatch_bools(F&& f, bool first, Rest... rest) {
    if (first)
        dispatch_bools<Fixed..., true>(f, rest...);
    else
        dispatch_bools<Fixed..., false>(f, rest...);
}

}  // namespace emergent::force

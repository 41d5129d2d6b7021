// SPDX-License-Identifier: MIT
// A profile of the device's work by loop: with EMERGENT_PROFILE=1 in the environment each
// kernel launch, reduction, scan and sort of the CUDA back end is timed alone (the device is
// synchronised before and after it, so the run is slower but each time is the call's own) and
// tallied by the functor's name; `emergent run` prints the table at the end. No cost when unset
// beyond one flag test per call.
#pragma once

#include <string>

namespace emergent::exec {

/// EMERGENT_PROFILE is set (to anything but 0).
bool profiling();
/// Seconds on a monotonic clock.
double profile_clock();
/// Adds one call of `what` (a kind: loop, reduce, scan, sort, copy) lasting `seconds`, named
/// `name`: a compiler's signature (functor_name; the functor's type is taken from it) or a
/// plain name.
void profile_add(const char* what, const char* name, double seconds);
/// The tallies, longest total first, with each one's share of their sum; empty when nothing
/// was profiled.
std::string profile_table();

}  // namespace emergent::exec

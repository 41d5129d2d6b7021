// SPDX-License-Identifier: MIT
// What a continued run may change of the run it continues.
#pragma once

#include <map>
#include <string>

#include "emergent/config.hpp"
#include "emergent/problem.hpp"

namespace emergent::app {

/// Compares a continued run's parameters with those its checkpoint was written with. A changed
/// structural (or unmarked) parameter throws InputError naming it; the adjustable ones that
/// changed are returned as one line ("continuing with changed parameters: dt 0.005 -> 0.004,
/// ..."), empty when none did. Numbers compare by value ("0.5" equals "5e-1").
std::string restart_changes(const ProblemInfo& info,
                            const std::map<std::string, std::string>& saved, const Config& now);

/// Adds to a checkpoint's parameters those it predates that record an earlier value
/// (ParamSpec::earlier_value): the run continues as it was built, not with a later default,
/// and a new value is refused like any structural change.
void add_earlier_values(const ProblemInfo& info, std::map<std::string, std::string>& saved);

}  // namespace emergent::app

// SPDX-License-Identifier: MIT
// Structural parameters stay; adjustable ones may change and are echoed.
#include "app/restart_changes.hpp"

#include "emergent/error.hpp"

namespace emergent::app {

std::string restart_changes(const ProblemInfo& info,
                            const std::map<std::string, std::string>& saved, const Config& now) {
    std::string changed;
    for (const ParamSpec& p : info.schema.params()) {
        const auto was = saved.find(p.name);
        if (was == saved.end()) continue;  // a parameter newer than the checkpoint
        const std::string& value = now.text(p.name);
        const bool numeric = p.type == ParamType::Integer || p.type == ParamType::Real;
        const bool same = numeric ? parse_number(p.name, was->second) == parse_number(p.name, value)
                                  : was->second == value;
        if (same) continue;
        if (p.restart != RestartRule::Adjustable)
            throw InputError("--restart: " + p.name + " is structural (the checkpoint was written with " +
                             p.name + "=" + was->second + "); a continued run cannot set it to " +
                             value + ": start a new run instead");
        changed += (changed.empty() ? "" : ", ") + p.name + " " + was->second + " -> " + value;
    }
    return changed.empty() ? "" : "continuing with changed parameters: " + changed;
}

void add_earlier_values(const ProblemInfo& info, std::map<std::string, std::string>& saved) {
    for (const ParamSpec& p : info.schema.params())
        if (!p.earlier_value.empty()) saved.emplace(p.name, p.earlier_value);
}

}  // namespace emergent::app

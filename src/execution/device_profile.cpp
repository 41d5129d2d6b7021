// SPDX-License-Identifier: MIT
#include "emergent/device_profile.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <utility>
#include <vector>

namespace emergent::exec {

namespace {
struct Tally {
    long long calls = 0;
    double seconds = 0;
};
std::map<std::string, Tally>& tallies() {
    static std::map<std::string, Tally> t;
    return t;
}

/// "... [with Functor = emergent::integrate::KickDrift]" -> "integrate::KickDrift"; a name
/// that is no signature (a copy's) stays as it is.
std::string functor_of(const char* signature) {
    std::string s(signature);
    const std::size_t with = s.find("[with ") != std::string::npos ? s.find(" = ") : std::string::npos;
    if (with != std::string::npos) {
        s = s.substr(with + 3);
        int depth = 0;
        std::size_t end = 0;
        for (; end < s.size(); ++end) {
            const char c = s[end];
            if (c == '<' || c == '(') ++depth;
            else if (c == '>' || c == ')') --depth;
            else if ((c == ']' || c == ';') && depth == 0) break;
        }
        s.resize(end);
    }
    for (const char* drop : {"emergent::", "exec::", "(anonymous namespace)::"})
        for (std::size_t at; (at = s.find(drop)) != std::string::npos;) s.erase(at, std::strlen(drop));
    if (s.size() > 100) s = s.substr(0, 97) + "...";
    return s;
}
}  // namespace

bool profiling() {
    static const bool on = [] {
        const char* v = std::getenv("EMERGENT_PROFILE");
        return v && *v && std::strcmp(v, "0") != 0;
    }();
    return on;
}

double profile_clock() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void profile_add(const char* what, const char* name, double seconds) {
    Tally& t = tallies()[std::string(what) + "  " + functor_of(name)];
    ++t.calls;
    t.seconds += seconds;
}

std::string profile_table() {
    if (tallies().empty()) return {};
    std::vector<std::pair<std::string, Tally>> rows(tallies().begin(), tallies().end());
    std::sort(rows.begin(), rows.end(),
              [](const auto& a, const auto& b) { return a.second.seconds > b.second.seconds; });
    double sum = 0;
    for (const auto& r : rows) sum += r.second.seconds;
    std::string out;
    char line[256];
    std::snprintf(line, sizeof line,
                  "# device profile (EMERGENT_PROFILE): each call alone; %.4f s in calls, share of their sum\n",
                  sum);
    out += line;
    out += "#   total_s    share    calls   us_per_call  what  functor\n";
    for (const auto& [name, t] : rows) {
        std::snprintf(line, sizeof line, "%10.4f  %6.2f%%  %7lld  %12.2f  ", t.seconds,
                      100 * t.seconds / sum, t.calls, 1e6 * t.seconds / double(t.calls));
        out += line + name + "\n";
    }
    return out;
}

}  // namespace emergent::exec

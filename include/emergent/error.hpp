// SPDX-License-Identifier: MIT
// The two kinds of failure: bad user input (collective) and rank-local faults (abort).
#pragma once

#include <stdexcept>
#include <string>

namespace emergent {

/// Bad input detected identically on every rank (unknown key, value out of range, impossible
/// geometry, unreadable file). main() prints the message once, on rank 0, and exits non-zero.
class InputError : public std::runtime_error {
public:
    explicit InputError(const std::string& what) : std::runtime_error(what) {}
};

/// The run became physically invalid (non-finite state, energy drift beyond its bound), as
/// seen identically by every rank after a reduction. Reported once, exit non-zero.
class InstabilityError : public std::runtime_error {
public:
    explicit InstabilityError(const std::string& what) : std::runtime_error(what) {}
};

/// A fault that may be seen by one rank only (particle lost, non-finite state). main() prints
/// it with the rank and the place that raised it, then aborts all ranks.
class RuntimeFault : public std::runtime_error {
public:
    RuntimeFault(const std::string& what, const char* where)
        : std::runtime_error(what), where_(where) {}
    const char* where() const { return where_; }

private:
    const char* where_;
};

}  // namespace emergent

// SPDX-License-Identifier: MIT
// How a run fails: bad user input, an unstable run, a rank-local fault, a failed file operation.
// main() turns each into one line and an exit code:
//   0 success; 2 bad input (InputError, a bad command line); 3 run-time fault (InstabilityError,
//   RuntimeFault, out of memory, any other internal error); 4 I/O failure (IoError).
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

/// A file could not be written or read back while the run was going (disk full, permissions,
/// an HDF5 write failing). Unreadable *input* files (config, checkpoint) are InputErrors.
class IoError : public std::runtime_error {
public:
    explicit IoError(const std::string& what) : std::runtime_error(what) {}
};

/// Exit codes of the `emergent` command (documented in docs/running.md, "Exit codes").
namespace exit_code {
inline constexpr int ok = 0;
inline constexpr int bad_input = 2;
inline constexpr int run_fault = 3;
inline constexpr int io_failure = 4;
inline constexpr int stopped = 5;  ///< stopped on request (a signal) with a checkpoint to continue
}  // namespace exit_code

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

// SPDX-License-Identifier: MIT
// Ends a failed command with one line for the user, whichever ranks failed.
#pragma once

#include <mpi.h>

#include <string>

namespace emergent::app {

/// Reports a failure caught on this rank and returns the exit code (or aborts the job).
/// `errors` is a communicator used for nothing else, so that waiting on it cannot be confused
/// with a collective the other ranks may be in.
/// - Every rank failed (input seen identically everywhere, a guard after a reduction): they meet
///   within `wait_seconds`; rank 0 prints its line and every rank returns `code`.
/// - Only some ranks failed (a file missing on one node, a rank-local fault): the others are
///   running or blocked in a collective, so a failing rank prints its line with its rank and
///   aborts the job with `code`. `rank_local` faults skip the wait.
int report_failure(MPI_Comm errors, int code, const std::string& line, bool rank_local,
                   double wait_seconds = 5.0);

}  // namespace emergent::app

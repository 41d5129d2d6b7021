// SPDX-License-Identifier: MIT
// Whether every rank reaches the same point, without waiting forever for one that never does.
#pragma once

#include <mpi.h>

namespace emergent::decomp {

/// True when every rank of `comm` calls this within `wait_seconds` (a non-blocking barrier,
/// polled). `comm` must be used for nothing else (a communicator of its own): a rank that
/// never comes may be inside another collective, which a barrier on the same communicator
/// could be confused with. When false the barrier stays pending: the caller is expected to
/// end the job.
bool ranks_meet(MPI_Comm comm, double wait_seconds);

}  // namespace emergent::decomp

// SPDX-License-Identifier: MIT
// MPI_Sendrecv with the sent message counted (emergent/message_counts.hpp).
#pragma once

#include <mpi.h>

#include <cstddef>

#include "emergent/message_counts.hpp"

namespace emergent::decomp {

/// Sends `send_bytes` to `to` and receives `recv_bytes` from `from`; counts the sent message in
/// `tally` unless `to` is MPI_PROC_NULL (a face without a neighbour).
inline void send_receive(const void* send, std::size_t send_bytes, int to, void* recv,
                         std::size_t recv_bytes, int from, int tag, MPI_Comm comm,
                         MessageCounts& tally) {
    MPI_Sendrecv(send, static_cast<int>(send_bytes), MPI_BYTE, to, tag, recv,
                 static_cast<int>(recv_bytes), MPI_BYTE, from, tag, comm, MPI_STATUS_IGNORE);
    if (to == MPI_PROC_NULL) return;
    ++tally.messages;
    tally.bytes += static_cast<long long>(send_bytes);
}

}  // namespace emergent::decomp

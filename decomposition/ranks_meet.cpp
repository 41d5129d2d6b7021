// SPDX-License-Identifier: MIT
#include "ranks_meet.hpp"

#include <chrono>
#include <thread>

namespace emergent::decomp {

bool ranks_meet(MPI_Comm comm, double wait_seconds) {
    int size = 1;
    MPI_Comm_size(comm, &size);
    if (size == 1) return true;
    MPI_Request request;
    MPI_Ibarrier(comm, &request);
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(wait_seconds);
    int done = 0;
    while (!done && std::chrono::steady_clock::now() < until) {
        MPI_Test(&request, &done, MPI_STATUS_IGNORE);
        if (!done) std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    return done != 0;
}

}  // namespace emergent::decomp

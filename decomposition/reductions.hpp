// SPDX-License-Identifier: MIT
// Global reductions over the ranks of a communicator, each counted in the step ledger
// (exec::count_collective).
#pragma once

#include <mpi.h>

#include <limits>
#include <string>

#include "emergent/execution.hpp"

namespace emergent::decomp {

inline double sum(MPI_Comm comm, double local) {
    double global = 0;
    exec::count_collective();
    MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, comm);
    return global;
}

inline long long sum(MPI_Comm comm, long long local) {
    long long global = 0;
    exec::count_collective();
    MPI_Allreduce(&local, &global, 1, MPI_LONG_LONG, MPI_SUM, comm);
    return global;
}

inline void sum_in_place(MPI_Comm comm, double* values, int n) {
    exec::count_collective();
    MPI_Allreduce(MPI_IN_PLACE, values, n, MPI_DOUBLE, MPI_SUM, comm);
}

inline double max(MPI_Comm comm, double local) {
    double global = 0;
    exec::count_collective();
    MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_MAX, comm);
    return global;
}

/// The message of the lowest rank whose `local` is non-empty, on every rank; empty if none.
/// Lets a fault seen by one rank stop all ranks together, with one clear message.
inline std::string first_message(MPI_Comm comm, const std::string& local) {
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    int first = local.empty() ? std::numeric_limits<int>::max() : rank;
    exec::count_collective();
    MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, comm);
    if (first == std::numeric_limits<int>::max()) return {};
    int length = static_cast<int>(local.size());
    exec::count_collective();
    MPI_Bcast(&length, 1, MPI_INT, first, comm);
    std::string message = rank == first ? local : std::string(length, ' ');
    exec::count_collective();
    MPI_Bcast(message.data(), length, MPI_CHAR, first, comm);
    return message;
}

}  // namespace emergent::decomp

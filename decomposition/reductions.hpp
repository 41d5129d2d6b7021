// SPDX-License-Identifier: MIT
// Global reductions over the ranks of a communicator.
#pragma once

#include <mpi.h>

namespace emergent::decomp {

inline double sum(MPI_Comm comm, double local) {
    double global = 0;
    MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, comm);
    return global;
}

inline long long sum(MPI_Comm comm, long long local) {
    long long global = 0;
    MPI_Allreduce(&local, &global, 1, MPI_LONG_LONG, MPI_SUM, comm);
    return global;
}

inline void sum_in_place(MPI_Comm comm, double* values, int n) {
    MPI_Allreduce(MPI_IN_PLACE, values, n, MPI_DOUBLE, MPI_SUM, comm);
}

inline double max(MPI_Comm comm, double local) {
    double global = 0;
    MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_MAX, comm);
    return global;
}

}  // namespace emergent::decomp


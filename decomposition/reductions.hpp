// SPDX-License-Identifier: MIT
// Global reductions over the ranks of a communicator, each counted in the step ledger
// (exec::count_collective).
#pragma once

#include <mpi.h>

#include <array>
#include <limits>
#include <stdexcept>
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

/// A step's vote and its sums in one collective: of `n` values the first kVoteMaxima are reduced
/// as maxima (a NaN wins, exec::max_keeping_nan), the rest summed. The values travel as one
/// element of a contiguous type, so the operation sees the whole vector however MPI splits work.
constexpr int kVoteMaxima = 2;
namespace detail {
inline void max_then_sum(void* in, void* inout, int* len, MPI_Datatype* type) {
    int bytes = 0;
    MPI_Type_size(*type, &bytes);
    const int n = bytes / int(sizeof(double));
    const double* a = static_cast<const double*>(in);
    double* b = static_cast<double*>(inout);
    for (int e = 0; e < *len; ++e, a += n, b += n)
        for (int k = 0; k < n; ++k) b[k] = k < kVoteMaxima ? exec::max_keeping_nan(a[k], b[k]) : a[k] + b[k];
}
}  // namespace detail
inline void max_then_sum_in_place(MPI_Comm comm, double* values, int n) {
    static MPI_Op op = [] {
        MPI_Op made;
        MPI_Op_create(&detail::max_then_sum, 1, &made);
        return made;
    }();
    // One committed type per length, made on first use and kept for the run.
    static std::array<MPI_Datatype, 64> types = [] {
        std::array<MPI_Datatype, 64> none;
        none.fill(MPI_DATATYPE_NULL);
        return none;
    }();
    if (n < kVoteMaxima || n >= int(types.size())) throw std::invalid_argument("max_then_sum_in_place: bad length");
    if (types[n] == MPI_DATATYPE_NULL) {
        MPI_Type_contiguous(n, MPI_DOUBLE, &types[n]);
        MPI_Type_commit(&types[n]);
    }
    exec::count_collective();
    MPI_Allreduce(MPI_IN_PLACE, values, 1, types[n], op, comm);
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

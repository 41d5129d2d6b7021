// SPDX-License-Identifier: MIT
// Sums whose result does not depend on the rank count or the order of the terms.
#pragma once

#include <mpi.h>

#include <cmath>

#include "emergent/execution.hpp"

namespace emergent::decomp {
__extension__ typedef __int128 Int128;  // GCC/Clang extension: exact 128-bit accumulation
}  // namespace emergent::decomp

namespace emergent::decomp {

/// Order-independent sum: each term is rounded to a multiple of 2^-32 and accumulated exactly
/// in 128-bit integers, so the total is bitwise the same for any rank count and particle
/// order. Terms must satisfy |x| < 2^31. Used where results must not depend on the
/// decomposition at all (the initial state).
class ExactSum {
public:
    void add(double x) { total_ += static_cast<Int128>(std::llround(std::ldexp(x, 32))); }

    /// Sum over all ranks of `comm`.
    double global(MPI_Comm comm) const {
        // Two's-complement 128-bit value as two 64-bit words; summed with carry by a custom op.
        long long words[2] = {static_cast<long long>(static_cast<unsigned long long>(total_)),
                              static_cast<long long>(total_ >> 64)};
        long long out[2] = {0, 0};
        MPI_Op op;
        MPI_Op_create(&add_words, 1, &op);
        exec::count_collective();
        MPI_Allreduce(words, out, 1, word_pair_type(), op, comm);
        MPI_Op_free(&op);
        const Int128 sum = (static_cast<Int128>(out[1]) << 64) |
                             static_cast<unsigned long long>(out[0]);
        return std::ldexp(static_cast<double>(sum), -32);
    }

private:
    static MPI_Datatype word_pair_type() {
        static MPI_Datatype type = [] {
            MPI_Datatype t;
            MPI_Type_contiguous(2, MPI_LONG_LONG, &t);
            MPI_Type_commit(&t);
            return t;
        }();
        return type;
    }
    static void add_words(void* in, void* inout, int* len, MPI_Datatype*) {
        auto* a = static_cast<long long*>(in);
        auto* b = static_cast<long long*>(inout);
        for (int k = 0; k < *len; ++k) {
            const Int128 x = (static_cast<Int128>(a[2 * k + 1]) << 64) |
                               static_cast<unsigned long long>(a[2 * k]);
            const Int128 y = (static_cast<Int128>(b[2 * k + 1]) << 64) |
                               static_cast<unsigned long long>(b[2 * k]);
            const Int128 s = x + y;
            b[2 * k] = static_cast<long long>(static_cast<unsigned long long>(s));
            b[2 * k + 1] = static_cast<long long>(s >> 64);
        }
    }

    Int128 total_ = 0;
};

}  // namespace emergent::decomp

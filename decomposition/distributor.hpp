// SPDX-License-Identifier: MIT
// Sends each element to a chosen rank: the all-to-all plan behind id-ordered file layout and
// restarts on any rank count.
#pragma once

#include <mpi.h>

#include <cstddef>
#include <vector>

namespace emergent::decomp {

/// A plan that sends local element k to rank destination[k] (Cabana's Distributor).
/// Imported elements arrive grouped by source rank, each group in the source's local order.
class Distributor {
public:
    Distributor(MPI_Comm comm, const std::vector<int>& destination);

    std::size_t n_export() const { return order_.size(); }
    std::size_t n_import() const { return n_import_; }

    /// Sends `element_bytes`-sized elements of `send` (n_export of them) and fills `recv`
    /// (room for n_import). Collective.
    void apply(const void* send, std::size_t element_bytes, void* recv) const;

    /// Typed convenience: returns the imported elements.
    template <class T>
    std::vector<T> apply(const std::vector<T>& send) const {
        std::vector<T> recv(n_import_);
        apply(send.data(), sizeof(T), recv.data());
        return recv;
    }

private:
    MPI_Comm comm_;
    std::vector<int> order_;  ///< local indices sorted by destination (stable)
    std::vector<int> send_count_, recv_count_, send_offset_, recv_offset_;
    std::size_t n_import_ = 0;
};

/// Ids [0, n_global) split into one contiguous block per rank: rank r writes or reads
/// ids [first(r), first(r + 1)).
struct IdBlocks {
    long long n_global = 0;
    int n_ranks = 1;
    long long first(int rank) const { return rank * n_global / n_ranks; }
    int owner(long long id) const;
};

}  // namespace emergent::decomp

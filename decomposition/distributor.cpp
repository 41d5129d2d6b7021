// SPDX-License-Identifier: MIT
// All-to-all distribution plan.
#include "distributor.hpp"

#include <algorithm>
#include <cstring>
#include <numeric>
#include <stdexcept>

namespace emergent::decomp {

Distributor::Distributor(MPI_Comm comm, const std::vector<int>& destination) : comm_(comm) {
    int n_ranks = 1;
    MPI_Comm_size(comm, &n_ranks);
    send_count_.assign(n_ranks, 0);
    for (int d : destination) {
        if (d < 0 || d >= n_ranks) throw std::logic_error("Distributor: destination out of range");
        ++send_count_[d];
    }
    order_.resize(destination.size());
    std::iota(order_.begin(), order_.end(), 0);
    std::stable_sort(order_.begin(), order_.end(),
                     [&](int a, int b) { return destination[a] < destination[b]; });
    recv_count_.assign(n_ranks, 0);
    MPI_Alltoall(send_count_.data(), 1, MPI_INT, recv_count_.data(), 1, MPI_INT, comm);
    send_offset_.assign(n_ranks, 0);
    recv_offset_.assign(n_ranks, 0);
    for (int r = 1; r < n_ranks; ++r) {
        send_offset_[r] = send_offset_[r - 1] + send_count_[r - 1];
        recv_offset_[r] = recv_offset_[r - 1] + recv_count_[r - 1];
    }
    n_import_ = static_cast<std::size_t>(recv_offset_.back() + recv_count_.back());
}

void Distributor::apply(const void* send, std::size_t element_bytes, void* recv) const {
    std::vector<char> packed(order_.size() * element_bytes);
    const auto* src = static_cast<const char*>(send);
    for (std::size_t k = 0; k < order_.size(); ++k)
        std::memcpy(&packed[k * element_bytes], src + order_[k] * element_bytes, element_bytes);
    // Counts in bytes: one MPI_BYTE call serves every element type.
    const int n = static_cast<int>(send_count_.size());
    std::vector<int> sc(n), so(n), rc(n), ro(n);
    for (int r = 0; r < n; ++r) {
        sc[r] = static_cast<int>(send_count_[r] * element_bytes);
        so[r] = static_cast<int>(send_offset_[r] * element_bytes);
        rc[r] = static_cast<int>(recv_count_[r] * element_bytes);
        ro[r] = static_cast<int>(recv_offset_[r] * element_bytes);
    }
    MPI_Alltoallv(packed.data(), sc.data(), so.data(), MPI_BYTE, recv, rc.data(), ro.data(),
                  MPI_BYTE, comm_);
}

int IdBlocks::owner(long long id) const {
    int r = static_cast<int>(static_cast<long double>(id) * n_ranks / n_global);
    r = std::clamp(r, 0, n_ranks - 1);
    while (r > 0 && first(r) > id) --r;
    while (r + 1 < n_ranks && first(r + 1) <= id) ++r;
    return r;
}

}  // namespace emergent::decomp

// SPDX-License-Identifier: MIT
// Ghost positions refreshed on the back end.
#include "neighbour/backend_halo.hpp"

#include <mpi.h>
#if __has_include(<mpi-ext.h>)
#include <mpi-ext.h>  // Open MPI's extensions: the CUDA support query
#endif

#include <stdexcept>

#include "decomposition/ghost_image.hpp"
#include "emergent/execution.hpp"

namespace emergent::exec {

bool mpi_reads_device_memory() {
    // Asked at run time: the Open MPI a run loads may have CUDA support although the one
    // compiled against had not (Debian's has not).
#if defined(OMPI_HAVE_MPI_EXT_CUDA) && OMPI_HAVE_MPI_EXT_CUDA
    return MPIX_Query_cuda_support() == 1;
#else
    return false;
#endif
}

void BackendHalo::place(const decomp::HaloExchange& halo, ParticleMirror& mirror,
                        std::size_t upload_slot) {
    if (!halo.exports_on_host())
        throw std::logic_error("BackendHalo::place: the halo's export lists are not on the host");
    index_.clear();
    std::vector<std::size_t> first(1, 0), count;
    for (std::size_t k = 0; k < halo.plan().swaps.size(); ++k) {
        const std::vector<int>& e = halo.export_index(k);
        index_.insert(index_.end(), e.begin(), e.end());
        first.push_back(index_.size());
        count.push_back(e.size());
    }
    const int* all =
        static_cast<const int*>(mirror.upload(upload_slot, index_.data(), index_.size() * sizeof(int)));
    std::vector<const int*> index;
    for (std::size_t k = 0; k < count.size(); ++k) index.push_back(all + first[k]);
    place_on_backend(std::move(index), std::move(count));
}

void BackendHalo::place_on_backend(std::vector<const int*> index, std::vector<std::size_t> count) {
    swap_index_ = std::move(index);
    swap_count_ = std::move(count);
    refresh_ = Refresh::undecided;
}

void BackendHalo::place_roots(const int* root, const Vec3* shift, std::size_t n_owned, std::size_t n_ghost) {
    swap_index_.clear();
    swap_count_.clear();
    roots_ = root;
    shifts_ = shift;
    n_owned_ = n_owned;
    n_ghost_ = n_ghost;
    refresh_ = Refresh::from_roots;
}

void BackendHalo::trace_roots(const Target& target, const decomp::HaloExchange& halo,
                              ParticleMirror& mirror, std::size_t scratch_slot) {
    const decomp::HaloPlan& plan = halo.plan();
    n_owned_ = plan.n_owned;
    n_ghost_ = plan.n_ghost;
    int* roots = static_cast<int*>(mirror.scratch(scratch_slot + 1, n_ghost_ * sizeof(int)));
    Vec3* shifts = static_cast<Vec3*>(mirror.scratch(scratch_slot + 2, n_ghost_ * sizeof(Vec3)));
    // In swap order: a swap's sources among the ghosts were traced by the swaps before it.
    for (std::size_t k = 0; k < plan.swaps.size(); ++k) {
        const decomp::HaloSwap& swap = plan.swaps[k];
        exec::for_each(target, swap_count_.at(k),
                       decomp::GhostRoot{swap_index_[k], n_owned_, swap.import_first - n_owned_, roots, shifts,
                                         swap.route.shift});
    }
    roots_ = roots;
    shifts_ = shifts;
}

void BackendHalo::prepare(const Target& target, const decomp::HaloExchange& halo, ParticleMirror& mirror,
                          std::size_t scratch_slot) {
    if (refresh_ != Refresh::undecided) return;
    refresh_ = halo.plan().from_roots() ? Refresh::from_roots : Refresh::by_swaps;
    if (refresh_ == Refresh::from_roots) trace_roots(target, halo, mirror, scratch_slot);
}

void BackendHalo::gather(const Target& target, const decomp::HaloExchange& halo,
                         ParticleMirror& mirror, Vec3* x, bool is_position,
                         std::size_t scratch_slot) {
    prepare(target, halo, mirror, scratch_slot);
    if (refresh_ == Refresh::from_roots) {
        exec::for_each(target, n_ghost_, decomp::GhostFromRoot{x, roots_, shifts_, is_position, x + n_owned_});
        return;
    }
    const decomp::HaloPlan& plan = halo.plan();
    for (std::size_t k = 0; k < plan.swaps.size(); ++k) {
        const decomp::HaloSwap& swap = plan.swaps[k];
        const std::size_t n = swap_count_.at(k);
        const int* index = swap_index_[k];
        const Vec3 shift = is_position ? swap.route.shift : Vec3{0, 0, 0};
        if (swap.route.to_self) {
            // Sources are owned particles and earlier swaps' ghosts, all before import_first:
            // the copies can land in place.
            exec::for_each(target, n,
                           decomp::GhostImage{x, index, x + swap.import_first, plan.wedge, swap.route.turns,
                                              shift});
            continue;
        }
        Vec3* packed = static_cast<Vec3*>(mirror.scratch(scratch_slot, n * sizeof(Vec3)));
        exec::for_each(target, n,
                       decomp::GhostImage{x, index, packed, plan.wedge, swap.route.turns, shift});
        const std::size_t send_bytes = n * sizeof(Vec3), receive_bytes = swap.import_count * sizeof(Vec3);
        if (target.direct_mpi) {
            // MPI reads and writes the back end's memory: no staging; the packing kernel must
            // have finished first.
            synchronize(target);
            halo.exchange_bytes(k, packed, send_bytes, x + swap.import_first, receive_bytes);
            continue;
        }
        void* send = mirror.staging(0, send_bytes);
        void* receive = mirror.staging(1, receive_bytes);
        // Every rank takes part in every swap (its partner waits for it), but a face without
        // a neighbour (a wall) moves nothing: no copies then.
        if (n > 0) mirror.copy_to_host(send, packed, send_bytes);
        halo.exchange_bytes(k, send, send_bytes, receive, receive_bytes);
        if (swap.import_count > 0) mirror.copy_to_backend(x + swap.import_first, receive, receive_bytes);
    }
}

}  // namespace emergent::exec

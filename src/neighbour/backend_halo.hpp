// SPDX-License-Identifier: MIT
// Ghost positions refreshed where the particles live: the halo's plan (host code, made at each
// list build) is carried out on the back end's arrays. Copies to this rank's own ghosts
// (periodic and wedge images) never leave the back end; copies for other ranks are packed
// there, staged through page-locked host buffers for MPI and unpacked there (each crossing
// counted), or handed to MPI in device memory where MPI is CUDA-aware.
#pragma once

#include <cstddef>
#include <vector>

#include "decomposition/halo_exchange.hpp"
#include "emergent/execution.hpp"
#include "particles/particle_mirror.hpp"

namespace emergent::exec {

/// True when this process's MPI moves CUDA device memory itself (Open MPI with CUDA support,
/// asked at run time); else messages are staged through host memory.
bool mpi_reads_device_memory();

class BackendHalo {
public:
    /// After each halo build: every swap's export indices go to the back end as one array.
    void place(const decomp::HaloExchange& halo, ParticleMirror& mirror, std::size_t upload_slot);
    /// After a build on the back end: swap k's export indices are count[k] ints at index[k],
    /// already in the back end's memory.
    void place_on_backend(std::vector<const int*> index, std::vector<std::size_t> count);
    /// After a build that made the ghosts from their owned roots directly (one rank, no wedge:
    /// BackendListBuild): ghost g is root[g]'s image shifted by shift[g], both on the back end;
    /// the plan is refreshed from them in one pass, with nothing left to trace.
    void place_roots(const int* root, const Vec3* shift, std::size_t n_owned, std::size_t n_ghost);
    /// Ghost values of `field` (the back end's array) from their owners, along the plan:
    /// positions (shifted across periodic boundaries) or velocities (never shifted); both
    /// rotated across wedge faces. Uses the mirror's scratch slots scratch_slot to
    /// scratch_slot + 2.
    /// Where the plan allows it (decomp::HaloPlan::from_roots), the ghosts are traced back to
    /// their owned roots once per plan and refreshed in one pass from there
    /// (decomp::GhostFromRoot), the same bits as the swaps one after another.
    void gather(const Target& target, const decomp::HaloExchange& halo, ParticleMirror& mirror,
                Vec3* field, bool is_position, std::size_t scratch_slot);

    /// Decides how the current plan is refreshed, and traces its roots where it is from them:
    /// part of the build, so the steps that follow it do only their one pass (else the first
    /// gather() does it). Uses the scratch slots as gather() does.
    void prepare(const Target& target, const decomp::HaloExchange& halo, ParticleMirror& mirror,
                 std::size_t scratch_slot);

private:
    /// Traces the current plan's ghosts to their roots (on the back end).
    void trace_roots(const Target& target, const decomp::HaloExchange& halo, ParticleMirror& mirror,
                     std::size_t scratch_slot);

    /// How the current plan is refreshed, decided by prepare() or at its first refresh.
    enum class Refresh { undecided, from_roots, by_swaps } refresh_ = Refresh::undecided;
    const int* roots_ = nullptr;  ///< from_roots: each ghost's owned root and total shift
    const Vec3* shifts_ = nullptr;
    std::size_t n_owned_ = 0, n_ghost_ = 0;
    std::vector<int> index_;  ///< export indices of all swaps, swap after swap (place())
    std::vector<const int*> swap_index_;  ///< where swap k's are on the back end
    std::vector<std::size_t> swap_count_;
};

}  // namespace emergent::exec

// SPDX-License-Identifier: MIT
// Ghost particles: which owned particles each neighbour needs, and refreshing them each step.
#pragma once

#include <mpi.h>

#include <cstddef>
#include <vector>

#include "emergent/message_counts.hpp"
#include "emergent/particle_store.hpp"
#include "halo_plan.hpp"
#include "rank_grid.hpp"

namespace emergent::decomp {

/// Plan of the ghost (halo) exchange, built from positions and reused until the next rebuild.
///
/// Nomenclature: a rank *exports* copies of its particles that lie within `width` of a face
/// to the rank across that face, which *imports* them as ghosts. Faces are handled in the
/// order -x, +x, -y, +y, -z, +z, and each axis also re-exports the ghosts imported along the
/// earlier axes, so edge and corner ghosts arrive without diagonal messages. Crossing a
/// periodic boundary shifts the copy by one box length; with one rank along an axis the
/// rank exports to itself, which makes the periodic images. A wedge region (Box::wedge) adds,
/// between the y and z phases, two exchanges of a rank with itself across the cut faces, whose
/// copies are rotated about z. Nothing here knows what the fields mean, except that positions
/// are shifted and rotated, and velocities rotated, across those boundaries.
class HaloExchange {
public:
    /// Drops old ghosts, then imports ghosts for all particles within `width` of the local
    /// faces, carrying the fields in `fields` (position is always carried).
    void build(ParticleStore& store, const RankGrid& grid, double width, unsigned fields);

    /// Refreshes ghost positions from their owners along the plan of the last build.
    void gather_positions(ParticleStore& store) { gather(store.position, true); }
    /// Refreshes ghost velocities (rotated across wedge faces, never shifted: no boundary
    /// moves) along the same plan.
    void gather_velocities(ParticleStore& store) { gather(store.velocity, false); }

    /// A refresh of ghost positions (and velocities, if `velocities`) in stages, so that the
    /// caller computes while messages are in flight: begin_refresh() starts the first stage's
    /// swaps (the swaps that export only particles present when the stage starts: one axis's
    /// two faces), advance_refresh() waits for the stage in flight and starts the next,
    /// end_refresh() completes them all. Until end_refresh() the ghosts' fields are not to be
    /// read. Sends the same messages, with the same counts, as gather_positions() and
    /// gather_velocities().
    void begin_refresh(ParticleStore& store, bool velocities);
    void advance_refresh();
    void end_refresh();
    /// Lets MPI move the stage in flight along without waiting for it: large messages go by
    /// a handshake that advances only inside MPI calls, so the caller calls this now and then
    /// while it computes.
    void progress();
    /// Stages of a refresh along the current plan that exchange messages (at least 1): the
    /// number of advance_refresh() calls worth computing between.
    std::size_t refresh_stages() const;
    /// Seconds spent waiting for ghost data in refreshes since it was made (the blocking ones:
    /// their whole exchanges).
    double refresh_wait_seconds() const { return wait_seconds_; }

    /// Number of ghosts imported by the last build.
    std::size_t n_ghost() const { return plan_.n_ghost; }

    /// The plan of the last build (made by make_halo_plan, here or on a back end), which a back
    /// end follows to refresh ghosts where the particles live (exec::BackendHalo).
    const HaloPlan& plan() const { return plan_; }
    /// Swap k's export indices, where the plan was made here.
    const std::vector<int>& export_index(std::size_t k) const { return exports_.at(k); }
    /// Takes the plan of a build made where the particles live (a list build on the back end:
    /// exec::BackendListBuild). Its export lists stay there (exec::BackendHalo), so the host's
    /// refreshes below are refused until the next build().
    void adopt_plan(const RankGrid& grid, HaloPlan plan);
    /// False after adopt_plan(): the export lists are not here.
    bool exports_on_host() const { return !exports_elsewhere_; }
    const Wedge& wedge() const { return plan_.wedge; }
    /// Sends swap k's packed copies (host memory) and receives its ghosts' into `recv`.
    void exchange_bytes(std::size_t k, const void* send, std::size_t send_bytes, void* recv,
                        std::size_t recv_bytes) const;

    /// What this rank sent to others since it was made: refreshes (gather_* and
    /// exchange_bytes) and builds.
    const MessageCounts& refresh_traffic() const { return refresh_traffic_; }
    const MessageCounts& build_traffic() const { return build_traffic_; }

private:
    void gather(std::vector<Vec3>& field, bool is_position);

    /// What make_halo_plan() needs from the host's particles (halo_exchange.cpp).
    struct HostPlace;

    void pack_fields_shifted(ParticleStore& store, unsigned fields, const SwapRoute& route,
                             const std::vector<int>& exports, const Wedge& wedge, std::size_t stride);
    void exchange(const SwapRoute& route, const void* send, std::size_t send_bytes, void* recv,
                  std::size_t recv_bytes, int tag, MessageCounts& tally) const;

    /// The first swap after `first` that re-exports a ghost imported by a swap in
    /// [first, that swap): where the stage starting at `first` ends.
    std::size_t stage_end(std::size_t first) const;
    /// Whether swaps [first, end) exchange messages with another rank.
    bool sends_messages(std::size_t first, std::size_t end) const;
    /// Completes the stage in flight and starts the next stages up to one with messages.
    void post_stage();
    void post_one_stage();
    void wait_stage();

    MPI_Comm comm_ = MPI_COMM_NULL;
    HaloPlan plan_;
    std::vector<std::vector<int>> exports_;  ///< per swap, where the plan was made here
    std::vector<char> send_buffer_, recv_buffer_;
    std::vector<Vec3> send_vectors_;
    bool exports_elsewhere_ = false;  ///< adopt_plan(): the export lists are on the back end
    // The staged refresh in progress: its fields, the next swap to start, the requests and
    // per-swap send buffers of the stage in flight.
    std::vector<Vec3>* staged_position_ = nullptr;
    std::vector<Vec3>* staged_velocity_ = nullptr;
    std::size_t next_swap_ = 0, stage_begin_ = 0;
    std::vector<MPI_Request> requests_;
    std::vector<std::vector<Vec3>> stage_send_;
    mutable double wait_seconds_ = 0;
    // Counted in const refreshes (exchange_bytes) too.
    mutable MessageCounts refresh_traffic_, build_traffic_;
};

}  // namespace emergent::decomp

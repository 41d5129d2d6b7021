// SPDX-License-Identifier: MIT
// The halo's plan: its swaps in their one order and where each one's ghosts land, made by one
// function whether the particles live on the host or on a back end.
#pragma once

#include <mpi.h>

#include <cstddef>
#include <vector>

#include "rank_grid.hpp"

namespace emergent::decomp {

/// One swap of the halo: the face it exports from, where it sends and receives, and what it
/// does to the copies.
struct SwapRoute {
    int axis = 0;   ///< the face's axis; -1: a wedge's cut face (side 0: theta = 0)
    int side = 0;   ///< 0: the low face (copies go down), 1: the high face
    int send_rank = MPI_PROC_NULL, recv_rank = MPI_PROC_NULL;
    bool to_self = false;
    Vec3 shift{0, 0, 0};  ///< across a periodic boundary: one box length
    int turns = 0;        ///< wedge rotations of the copies (before the shift)
    /// The first swap of a phase: it and the rest of its phase export from the particles
    /// present now (an axis's two faces; the wedge's two cut faces).
    bool starts_phase = false;
    /// Whether it exchanges messages with another rank (not a copy to itself, not a wall).
    bool talks() const { return !to_self && (send_rank != MPI_PROC_NULL || recv_rank != MPI_PROC_NULL); }
};

/// The halo's swaps in their order: per axis its two faces, -x, +x, -y, +y, -z, +z, and a
/// wedge's two cut faces before z. Only make_halo_plan() and lone_domain_images() walk it.
std::vector<SwapRoute> halo_routes(const RankGrid& grid);

/// One swap of a made plan: its route, the copies it sends, and the ghosts it brought.
struct HaloSwap {
    SwapRoute route;
    std::size_t export_count = 0;
    std::size_t import_first = 0, import_count = 0;
};

/// The halo's plan, made at each list build and followed by every ghost refresh until the
/// next, on the host (decomp::HaloExchange) and on a back end (exec::BackendHalo) alike.
/// Ghosts are appended swap after swap: swap k's are [import_first, import_first +
/// import_count), after the owned particles [0, n_owned).
struct HaloPlan {
    std::vector<HaloSwap> swaps;
    Wedge wedge;
    std::size_t n_owned = 0, n_ghost = 0;

    /// Whether every swap is a rank's copy to itself with at most a shift along its own axis
    /// (one rank, periodic box, no wedge): a ghost's way then passes each axis at most once, so
    /// every ghost is its owned root shifted, and can be refreshed from it in one pass.
    bool from_roots() const;
};

/// Makes the halo's plan, route by route (halo_routes): both faces of a phase export from the
/// particles present when the phase began, so a ghost imported through -d is not sent straight
/// back through +d. What depends on where the particles live is `place`'s:
///   std::size_t size()             owned particles and ghosts made so far;
///   std::size_t select(route, k, n_candidates)
///                                  swap k's exports among the first n_candidates particles,
///                                  kept for refreshes; returns their number;
///   std::size_t move(route, k, n_export)
///                                  sends their copies (moved and turned as the route says),
///                                  appends the ghosts that arrive; returns their number.
template <class Place>
HaloPlan make_halo_plan(const RankGrid& grid, Place& place) {
    HaloPlan plan;
    plan.wedge = grid.global().wedge;
    plan.n_owned = place.size();
    std::size_t n_candidates = 0;
    for (const SwapRoute& route : halo_routes(grid)) {
        if (route.starts_phase) n_candidates = place.size();
        const std::size_t k = plan.swaps.size();
        HaloSwap swap{route, 0, 0, 0};
        swap.export_count = place.select(route, k, n_candidates);
        swap.import_first = place.size();
        swap.import_count = place.move(route, k, swap.export_count);
        plan.swaps.push_back(swap);
    }
    plan.n_ghost = place.size() - plan.n_owned;
    return plan;
}

/// Whether the domain is alone: one rank, no wedge, every face a copy to itself (periodic) or a
/// wall. Its ghosts can then be made in one pass from their owned roots (lone_domain_images).
bool lone_domain(const RankGrid& grid);

/// The ghosts of a lone domain by kind: a kind is the set of faces its particles are near (one
/// bit per face, 2 axis + side) and the shift that makes their image. make_halo_plan() would
/// make each kind in one of its swaps; here they are listed in the order it makes them, so that
/// a build counts every kind in one pass and lays the plan out from the counts (plan()).
struct LoneDomainImages {
    struct Kind {
        unsigned faces = 0;
        Vec3 shift{0, 0, 0};
    };
    std::vector<Kind> kinds;
    std::vector<SwapRoute> routes;
    std::vector<std::size_t> first_kind;  ///< swap k makes kinds [first_kind[k], first_kind[k + 1])
    Wedge wedge;

    /// The plan, from the number of ghosts of each kind (count[q] of kinds[q]).
    HaloPlan plan(std::size_t n_owned, const std::vector<std::size_t>& count) const;
};
/// For a lone domain (lone_domain(grid)); logic_error otherwise.
LoneDomainImages lone_domain_images(const RankGrid& grid);

}  // namespace emergent::decomp

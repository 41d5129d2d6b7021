// SPDX-License-Identifier: MIT
// The list build on the back end's arrays, step by step as the host's (Simulation's rebuild:
// migration, cell order, halo, cells, full list), each step a loop, scan or sort of the
// execution layer.
#include "neighbour/backend_list_build.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "decomposition/ghost_image.hpp"
#include "neighbour/list_build_loops.hpp"

namespace emergent {

namespace {
/// Bits of the largest of n values 0 .. n - 1 (at least 1): a radix sort's passes.
int bits_for(std::size_t n) {
    int bits = 1;
    while (bits < 32 && (std::size_t{1} << bits) < n) ++bits;
    return bits;
}
}  // namespace

bool BackendListBuild::applies(const decomp::RankGrid& grid, bool bodies) {
    return !bodies && grid.dims()[0] * grid.dims()[1] * grid.dims()[2] == 1;
}

bool BackendListBuild::build(const exec::Target& target, exec::ParticleMirror& mirror,
                             ParticleStore& store, const decomp::RankGrid& grid, const CellList& cells,
                             double ghost_width, double list_range, decomp::HaloExchange& halo,
                             exec::BackendHalo& backend_halo) {
    fault_.clear();
    mirror.to_backend(store, kAllFields & ~kForce);
    // The first sort is by id as a 32-bit key; larger ids (never made by the scenes here, but
    // allowed) leave the build to the host.
    const double largest_id = exec::transform_max(target, store.n_owned(), 0.0,
                                                  build::IdMagnitude{mirror.array<std::int64_t>(kId)});
    if (!(largest_id < 4294967296.0)) return false;
    mirror.resize_on_backend(store, 0);
    if (!come_home(target, mirror, store, grid)) return true;
    sort_by_cell_and_id(target, mirror, store, cells,
                        bits_for(static_cast<std::size_t>(largest_id) + 1));
    make_ghosts(target, mirror, store, grid, ghost_width, halo, backend_halo);
    list(target, mirror, store, cells, list_range);
    return true;
}

bool BackendListBuild::come_home(const exec::Target& target, exec::ParticleMirror& mirror,
                                 ParticleStore& store, const decomp::RankGrid& grid) {
    const std::size_t n = store.n_owned();
    int* fault = reinterpret_cast<int*>(buffer(mirror, kFaults, n));
    build::ComeHome home{mirror.array<Vec3>(kPosition), mirror.array<Vec3>(kVelocity),
                         mirror.array<Int3>(kImage), grid.global().wedge, grid.lo(), grid.hi(),
                         grid.global().length(), {0, 0, 0}, fault};
    for (int d = 0; d < 3; ++d) home.periodic[d] = grid.neighbour(d, 0) != MPI_PROC_NULL;
    exec::for_each(target, n, home);
    const double first = exec::transform_max(target, n, -1e300, build::FaultOrder{fault});
    if (first == -1e300) return true;
    const int code = static_cast<int>(-first);
    const std::size_t i = exec::first_index(target, n, build::HasFault{fault, code});
    const Vec3 x = exec::read_one(target, mirror.array<Vec3>(kPosition) + i);
    const std::int64_t id = exec::read_one(target, mirror.array<std::int64_t>(kId) + i);
    const int axis = (code - 1) / 3;
    const bool closed = (code - 1) % 3 == 0;
    std::ostringstream msg;
    msg << "particle id " << id << " at (" << x.x << ", " << x.y << ", " << x.z << ") "
        << (closed ? "left the region through a closed boundary"
                   : "moved more than a box length between list builds")
        << " along " << "xyz"[axis];
    fault_ = msg.str();
    return false;
}

void BackendListBuild::sort_by_cell_and_id(const exec::Target& target, exec::ParticleMirror& mirror,
                                           ParticleStore& store, const CellList& cells, int id_bits) {
    // By id, then stably by cell: the host's order (cells, ids ascending within each).
    const std::size_t n = store.n_owned();
    std::uint32_t* keys = buffer(mirror, kKeys, n);
    std::uint32_t* order = buffer(mirror, kValues, n);
    exec::for_each(target, n, build::IdKey{mirror.array<std::int64_t>(kId), keys, order});
    exec::sort_pairs(target, keys, order, n, id_bits);
    exec::for_each(target, n, build::CellKey{mirror.array<Vec3>(kPosition), cells.index(), keys, order, false});
    exec::sort_pairs(target, keys, order, n, bits_for(static_cast<std::size_t>(cells.n_cells())));
    // Every array but the forces (recomputed after a build) takes the new order.
    std::size_t widest = 0;
    mirror.for_each_array([&](FieldMask, std::size_t bytes, void*) { widest = std::max(widest, bytes); });
    std::uint32_t* moved = buffer(mirror, kGather, n * (widest / 4));
    mirror.for_each_array([&](FieldMask field, std::size_t bytes, void* data) {
        if (field == kForce) return;
        exec::for_each(target, n,
                       build::GatherWords<std::uint32_t>{static_cast<const std::uint32_t*>(data), moved,
                                                         order, static_cast<unsigned>(bytes / 4)});
        mirror.copy_within(data, moved, n * bytes);
    });
}

void BackendListBuild::append_images(const exec::Target& target, exec::ParticleMirror& mirror,
                                     ParticleStore& store, build::NearFace near, std::size_t n_candidates,
                                     decomp::HaloExchange::SwapPlan plan, const Wedge& wedge) {
    const std::size_t k = plans_.size();
    std::uint32_t* flag = buffer(mirror, kFlags, n_candidates + 1);
    near.flag = flag;
    near.n = n_candidates;
    exec::for_each(target, n_candidates + 1, near);
    const std::size_t count = exec::exclusive_scan(target, flag, flag, n_candidates + 1);
    int* index = reinterpret_cast<int*>(buffer(mirror, kSwapIndex0 + k, count));
    exec::for_each(target, n_candidates, build::Compact{flag, index});
    plan.import_first = store.size();
    plan.import_count = count;
    mirror.resize_on_backend(store, store.n_ghost() + count);
    Vec3* x = mirror.array<Vec3>(kPosition);
    // The owners' values of every field (ghosts carry what owners have), then positions moved
    // to the image and velocities turned, as HaloExchange does.
    mirror.for_each_array([&](FieldMask field, std::size_t bytes, void* data) {
        if (field == kForce || field == kPosition) return;
        const unsigned words = static_cast<unsigned>(bytes / 4);
        std::uint32_t* a = static_cast<std::uint32_t*>(data);
        exec::for_each(target, count, build::GatherWords<int>{a, a + plan.import_first * words, index, words});
    });
    exec::for_each(target, count,
                   decomp::GhostImage{x, index, x + plan.import_first, wedge, plan.turns, plan.shift});
    if (plan.turns) {
        Vec3* v = mirror.array<Vec3>(kVelocity);
        exec::for_each(target, count, build::TurnedCopy{v, index, v + plan.import_first, wedge, plan.turns});
    }
    plans_.push_back(plan);
    swap_index_.push_back(index);
    swap_count_.push_back(count);
}

void BackendListBuild::make_ghosts(const exec::Target& target, exec::ParticleMirror& mirror,
                                   ParticleStore& store, const decomp::RankGrid& grid, double width,
                                   decomp::HaloExchange& halo, exec::BackendHalo& backend_halo) {
    // HaloExchange::build's phases in its order (see there): per axis, both faces export from
    // the particles present when the axis began; the wedge's cut faces come before z.
    plans_.clear();
    swap_index_.clear();
    swap_count_.clear();
    const Vec3 lo = grid.lo(), hi = grid.hi(), len = grid.global().length();
    const Wedge& wedge = grid.global().wedge;
    for (int d = 0; d < 3; ++d) {
        if (d == 2 && wedge.active()) {
            const std::size_t n_candidates = store.size();
            for (int side = 0; side < 2; ++side) {
                build::NearFace near{mirror.array<Vec3>(kPosition), -1, side, 0, wedge, width, 0, nullptr};
                append_images(target, mirror, store, near, n_candidates,
                              {true, Vec3{0, 0, 0}, side == 0 ? 1 : -1, 0, 0}, wedge);
            }
        }
        const std::size_t n_candidates = store.size();
        for (int side = 0; side < 2; ++side) {
            decomp::HaloExchange::SwapPlan plan{false, Vec3{0, 0, 0}, 0, 0, 0};
            const bool open = grid.neighbour(d, side) != MPI_PROC_NULL;
            plan.to_self = open;  // one rank: an open face is this rank's own periodic image
            if (open && grid.wraps(d, side)) plan.shift[d] = side == 0 ? len[d] : -len[d];
            // A closed face exports nothing: its flags are all 0.
            const Real edge = !open ? (side == 0 ? -INFINITY : INFINITY)
                                    : (side == 0 ? lo[d] + width : hi[d] - width);
            build::NearFace near{mirror.array<Vec3>(kPosition), d, side, edge, wedge, 0, 0, nullptr};
            append_images(target, mirror, store, near, n_candidates, plan, wedge);
        }
    }
    halo.adopt_plan(grid, plans_);
    backend_halo.place_on_backend(swap_index_, swap_count_);
}

void BackendListBuild::list(const exec::Target& target, exec::ParticleMirror& mirror,
                            const ParticleStore& store, const CellList& cells, double list_range) {
    const std::size_t n = store.size(), n_owned = store.n_owned();
    const CellIndex grid = cells.index();
    const std::size_t n_cells = static_cast<std::size_t>(grid.n_cells());
    const Vec3* x = mirror.array<Vec3>(kPosition);
    // Bins: every particle by cell, in index order within a cell (a stable sort of the
    // identity by cell), and where each cell's members begin.
    std::uint32_t* keys = buffer(mirror, kKeys, n);
    std::uint32_t* member = buffer(mirror, kValues, n);
    exec::for_each(target, n, build::CellKey{x, grid, keys, member, true});
    exec::sort_pairs(target, keys, member, n, bits_for(n_cells));
    std::uint32_t* start = buffer(mirror, kCellStart, n_cells + 1);
    exec::for_each(target, n_cells + 1, build::CellStart{keys, n, start});
    // Count, scan to offsets, list.
    const std::int64_t* body = store.has_rigid_fields() ? mirror.array<std::int64_t>(kBody) : nullptr;
    std::uint32_t* offset = buffer(mirror, kOffsets, n_owned + 1);
    build::ListNeighbours search{x, body, grid, start, member, list_range * list_range, n_owned, nullptr, offset};
    exec::for_each(target, n_owned + 1, search);
    n_pairs_ = exec::exclusive_scan(target, offset, offset, n_owned + 1);
    std::uint32_t* neighbours = buffer(mirror, kNeighbours, n_pairs_);
    search.offset = offset;
    search.out = neighbours;
    exec::for_each(target, n_owned, search);
    offsets_ = offset;
    neighbours_ = neighbours;
    Vec3* reference = static_cast<Vec3*>(mirror.scratch(slot_ + kReference, n_owned * sizeof(Vec3)));
    mirror.copy_within(reference, x, n_owned * sizeof(Vec3));
    reference_ = reference;
}

}  // namespace emergent

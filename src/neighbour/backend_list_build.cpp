// SPDX-License-Identifier: MIT
// The list build on the back end's arrays, step by step as the host's (Simulation's rebuild:
// migration, cell order, halo, cells, full list), each step a loop, scan or sort of the
// execution layer; what crosses a domain face is packed on the back end and staged through
// host memory for MPI.
#include "neighbour/backend_list_build.hpp"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "decomposition/ghost_image.hpp"
#include "decomposition/message_tally.hpp"
#include "decomposition/migration.hpp"
#include "decomposition/reductions.hpp"
#include "neighbour/list_build_loops.hpp"

namespace emergent {

namespace {
using build::key_bits;
constexpr int kCountTag = 7301, kDataTag = 7302;
// The mirror's staging buffers this build uses (BackendHalo's refresh uses 0 and 1).
constexpr std::size_t kStageSend = 2, kStageReceive = 3;
}  // namespace

bool BackendListBuild::build(const exec::Target& target, exec::ParticleMirror& mirror,
                             ParticleStore& store, const decomp::RankGrid& grid, const CellList& cells,
                             double ghost_width, double list_range, decomp::HaloExchange& halo,
                             exec::BackendHalo& backend_halo, const Bodies* bodies) {
    fault_.clear();
    mirror.to_backend(store, kAllFields & ~kForce);
    if (bodies) bodies->mirror->to_backend(*bodies->store, kAllFields & ~(kForce | kTorque));
    // The host's arrays are sized once, at the end (or on any way out).
    const exec::ParticleMirror::DeferredResize particles_sized(mirror, store);
    std::optional<exec::ParticleMirror::DeferredResize> bodies_sized;
    if (bodies) bodies_sized.emplace(*bodies->mirror, *bodies->store);
    if (!bodies && one_domain(grid))
        return build_one_domain(target, mirror, store, grid, cells, ghost_width, list_range, halo, backend_halo);
    // The first sort is by id as a 32-bit key; larger ids (never made by the scenes here, but
    // allowed) leave the build to the host, on every rank.
    double largest_id = exec::transform_max(target, store.n_owned(), 0.0,
                                            build::IdMagnitude{mirror.array<std::int64_t>(kId)});
    largest_id = decomp::max(grid.comm(), largest_id);
    if (!(largest_id < 4294967296.0)) return false;
    mirror.resize_on_backend(store, store.n_owned(), 0);
    // With bodies: their constituents go, free particles and then bodies migrate (as the host's
    // decomp::Migration moves each), their constituents come back after the free ones
    // (RigidBodies' order).
    if (bodies) drop_constituents(target, mirror, store);
    const Int3 dims = grid.dims();
    const bool alone = dims[0] * dims[1] * dims[2] == 1;
    const auto started = std::chrono::steady_clock::now();  // the migrations, timed (PhaseTimes)
    if (alone)
        come_home(target, mirror, store, grid);
    else
        migrate(target, mirror, store, grid);
    // Every rank stops together, with the first rank's message (as decomp::Migration).
    fault_ = decomp::first_message(grid.comm(), fault_);
    if (!fault_.empty()) return true;
    if (bodies) {
        if (alone)
            come_home(target, *bodies->mirror, *bodies->store, grid);
        else
            migrate(target, *bodies->mirror, *bodies->store, grid);
        fault_ = decomp::first_message(grid.comm(), fault_);
        if (!fault_.empty()) return true;
    }
    migration_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    if (bodies) {
        n_free_ = store.n_owned();  // the free particles this rank holds after their migration
        // Coming home changes where bodies are; migrating also which bodies this rank holds,
        // so every body field the host holds is stale (forces and torques are summed anew).
        bodies->mirror->written_on_backend(*bodies->store,
                                           alone ? kPosition | kVelocity | kImage : bodies->fields);
        append_constituents(target, mirror, store, *bodies);
    }
    const std::uint32_t* order = sort_by_cell_and_id(target, mirror, store, cells,
                                                     key_bits(static_cast<std::size_t>(largest_id) + 1));
    if (bodies) {
        // Where the appended constituents went in the sort: the index the bodies' loops use.
        const std::size_t n = store.n_owned(), n_constituents = n - n_free_;
        std::uint32_t* new_of_old = buffer(mirror, kNewOfOld, n);
        exec::for_each(target, n, build::InvertOrder{order, new_of_old});
        std::uint32_t* index = buffer(mirror, kConstituentIndex, n_constituents);
        exec::for_each(target, n_constituents, build::MovedSlots{new_of_old, n_free_, index});
        constituents_.index = index;
    }
    make_ghosts(target, mirror, store, grid, ghost_width, halo, backend_halo);
    list(target, mirror, store, cells, list_range);
    return true;
}

bool BackendListBuild::build_one_domain(const exec::Target& target, exec::ParticleMirror& mirror,
                                        ParticleStore& store, const decomp::RankGrid& grid, const CellList& cells,
                                        double ghost_width, double list_range, decomp::HaloExchange& halo,
                                        exec::BackendHalo& backend_halo) {
    mirror.resize_on_backend(store, store.n_owned(), 0);
    const std::size_t n = store.n_owned();
    const auto started = std::chrono::steady_clock::now();
    int* fault = reinterpret_cast<int*>(buffer(mirror, kFaults, n));
    // The keys live where the gather that follows the sort packs the particles (dead by then).
    auto* key = reinterpret_cast<std::uint64_t*>(buffer(mirror, kGather, 2 * n));
    std::uint32_t* order = buffer(mirror, kValues, n);
    build::ComeHome home{mirror.array<Vec3>(kPosition), mirror.array<Vec3>(kVelocity),
                         mirror.array<Int3>(kImage), grid.global().wedge, grid.lo(), grid.hi(),
                         grid.global().length(), {0, 0, 0}, fault};
    for (int d = 0; d < 3; ++d) home.periodic[d] = grid.neighbour(d, 0) != MPI_PROC_NULL;
    exec::for_each(target, n,
                   build::ComeHomeAndKey{home, mirror.array<std::int64_t>(kId), cells.index(), key, order});
    migration_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    exec::sort_pairs(target, key, order, n, 32 + key_bits(static_cast<std::size_t>(cells.n_cells())));
    gather_owned(target, mirror, store, reinterpret_cast<const int*>(order), n);
    const build::ImageCounts status =
        make_images(target, mirror, store, grid, ghost_width, halo, backend_halo, fault);
    // An id no key holds: the host builds (it repeats this migration and sort to the same end,
    // and orders by the whole id).
    if (status.ids_outside) return false;
    if (status.first_fault != ~std::uint64_t{0}) {
        // The first fault as the host's migration finds it (describe_fault); its particle has
        // moved in the sort since.
        const auto before = static_cast<std::uint32_t>(status.first_fault & 0xffffffffu);
        const std::size_t i = exec::first_index(target, n, build::WentTo{order, before});
        name_fault_code(target, mirror, i, static_cast<int>(status.first_fault >> 32), -1);
        return true;
    }
    list(target, mirror, store, cells, list_range);
    return true;
}

build::ImageCounts BackendListBuild::make_images(const exec::Target& target, exec::ParticleMirror& mirror,
                                                 ParticleStore& store, const decomp::RankGrid& grid, double width,
                                                 decomp::HaloExchange& halo, exec::BackendHalo& backend_halo,
                                                 const int* fault) {
    // The kinds in the order the halo's swaps would make them (decomp::LoneDomainImages).
    const decomp::LoneDomainImages images = decomp::lone_domain_images(grid);
    if (images.kinds.size() > static_cast<std::size_t>(build::kMaxImageKinds))
        throw std::logic_error("BackendListBuild: more kinds of image than a domain has");
    build::ImageKinds kinds;
    const Vec3 lo = grid.lo(), hi = grid.hi();
    for (int d = 0; d < 3; ++d) {
        kinds.edge[d][0] = lo[d] + width;
        kinds.edge[d][1] = hi[d] - width;
    }
    kinds.n = static_cast<int>(images.kinds.size());
    for (int q = 0; q < kinds.n; ++q) {
        kinds.need[q] = images.kinds[q].faces;
        kinds.shift[q] = images.kinds[q].shift;
    }
    const std::size_t n = store.n_owned(), n_blocks = (n + build::kImageBlock - 1) / build::kImageBlock,
                      rows = n_blocks + 1;
    std::uint32_t* first = buffer(mirror, kFlags, static_cast<std::size_t>(kinds.n) * rows);
    const build::ImageCounts counts = exec::transform_sum<build::ImageCounts>(
        target, rows, build::CountImages{mirror.array<Vec3>(kPosition), kinds, n, n_blocks, first, fault});
    if (counts.ids_outside || counts.first_fault != ~std::uint64_t{0}) return counts;
    exec::exclusive_scan_queued(target, first, first, static_cast<std::size_t>(kinds.n) * rows);
    decomp::HaloPlan plan = images.plan(n, std::vector<std::size_t>(counts.count, counts.count + kinds.n));
    const std::size_t n_ghost = plan.n_ghost;
    mirror.resize_on_backend(store, n, n_ghost);
    int* root = reinterpret_cast<int*>(buffer(mirror, kRoots, n_ghost));
    Vec3* total_shift = static_cast<Vec3*>(mirror.scratch(slot_ + kShifts, n_ghost * sizeof(Vec3)));
    build::FieldGather copies;
    mirror.for_each_array([&](FieldMask field, std::size_t bytes, void* data) {
        if (field == kForce || field == kPosition) return;
        std::uint32_t* a = static_cast<std::uint32_t*>(data);
        add_field(copies, a, a, static_cast<unsigned>(bytes / 4));
    });
    exec::for_each(target, n,
                   build::WriteImages{copies, mirror.array<Vec3>(kPosition), kinds, n, n_blocks, first, root,
                                      total_shift});
    halo.adopt_plan(grid, std::move(plan));
    backend_halo.place_roots(root, total_shift, n, n_ghost);
    return counts;
}

void BackendListBuild::describe_fault(const exec::Target& target, exec::ParticleMirror& mirror,
                                      std::size_t n, const int* fault, int axis) {
    if (!fault_.empty()) return;  // the first one found is reported
    const double first = exec::transform_max(target, n, -1e300, build::FaultOrder{fault});
    if (first == -1e300) return;
    const int code = static_cast<int>(-first);
    name_fault_code(target, mirror, exec::first_index(target, n, build::HasFault{fault, code}), code, axis);
}

void BackendListBuild::name_fault_code(const exec::Target& target, const exec::ParticleMirror& mirror,
                                       std::size_t i, int code, int axis) {
    // Codes: per axis 1 closed face, 2 and 3 long jumps through side 0 and 1; a one-pass
    // migration (axis < 0) numbers them on from 1 + 3 axis (build::fault_code).
    const int kind = axis < 0 ? (code - 1) % 3 + 1 : code;
    if (axis < 0) axis = (code - 1) / 3;
    name_fault(target, mirror, i, axis, kind == 1 ? decomp::kLeftThroughClosedFace : decomp::kMovedMoreThanABox);
}

void BackendListBuild::name_fault(const exec::Target& target, const exec::ParticleMirror& mirror, std::size_t i,
                                  int axis, const char* why) {
    fault_ = decomp::describe_leaver(exec::read_one(target, mirror.array<std::int64_t>(kId) + i),
                                     exec::read_one(target, mirror.array<Vec3>(kPosition) + i), axis, why);
}

void BackendListBuild::come_home(const exec::Target& target, exec::ParticleMirror& mirror,
                                 ParticleStore& store, const decomp::RankGrid& grid) {
    const std::size_t n = store.n_owned();
    int* fault = reinterpret_cast<int*>(buffer(mirror, kFaults, n));
    build::ComeHome home{mirror.array<Vec3>(kPosition), mirror.array<Vec3>(kVelocity),
                         mirror.array<Int3>(kImage), grid.global().wedge, grid.lo(), grid.hi(),
                         grid.global().length(), {0, 0, 0}, fault};
    for (int d = 0; d < 3; ++d) home.periodic[d] = grid.neighbour(d, 0) != MPI_PROC_NULL;
    exec::for_each(target, n, home);
    describe_fault(target, mirror, n, fault, -1);
}

unsigned BackendListBuild::packed_words(const exec::ParticleMirror& mirror) const {
    unsigned words = 0;
    mirror.for_each_array([&](FieldMask field, std::size_t bytes, void*) {
        if (field != kForce) words += static_cast<unsigned>(bytes / 4);
    });
    return words;
}

void BackendListBuild::pack(const exec::Target& target, exec::ParticleMirror& mirror, const int* index,
                            std::size_t count, std::uint32_t* out, bool image, const Vec3& shift,
                            int turns, const Wedge& wedge) {
    std::size_t offset = 0;
    // One pass: the fields copied as they are, and for ghosts the positions moved to their
    // image and the velocities turned.
    build::FieldGather plain;
    decomp::GhostImage position{nullptr, index, nullptr, wedge, turns, shift};
    build::TurnedCopy velocity{nullptr, index, nullptr, wedge, 0};  // turns 0: among the plain fields
    mirror.for_each_array([&](FieldMask field, std::size_t bytes, void* data) {
        if (field == kForce) return;
        const unsigned words = static_cast<unsigned>(bytes / 4);
        std::uint32_t* to = out + offset;
        if (image && field == kPosition) {
            position.in = static_cast<const Vec3*>(data);
            position.out = reinterpret_cast<Vec3*>(to);
        } else if (image && turns && field == kVelocity) {
            velocity = {static_cast<const Vec3*>(data), index, reinterpret_cast<Vec3*>(to), wedge, turns};
        } else {
            add_field(plain, static_cast<const std::uint32_t*>(data), to, words);
        }
        offset += count * words;
    });
    if (image)
        exec::for_each(target, count, build::GatherImages{{plain, index}, position, velocity});
    else
        exec::for_each(target, count, build::GatherFields<int>{plain, index});
}

void BackendListBuild::add_field(build::FieldGather& gather, const std::uint32_t* from, std::uint32_t* to,
                                 unsigned words) {
    if (!gather.add(from, to, words))
        throw std::logic_error("BackendListBuild: more particle arrays than fields");
}

void BackendListBuild::unpack(exec::ParticleMirror& mirror, const std::uint32_t* in, std::size_t count,
                              std::size_t first) {
    std::size_t offset = 0;
    mirror.for_each_array([&](FieldMask field, std::size_t bytes, void* data) {
        if (field == kForce) return;
        mirror.copy_within(static_cast<char*>(data) + first * bytes, in + offset, count * bytes);
        offset += count * (bytes / 4);
    });
}

std::size_t BackendListBuild::exchange(const exec::Target& target, exec::ParticleMirror& mirror, MPI_Comm comm,
                                       int to, int from, const std::uint32_t* packed, std::size_t count,
                                       std::size_t slot, const std::uint32_t** received,
                                       MessageCounts& tally) {
    const std::size_t record = packed_words(mirror) * sizeof(std::uint32_t);
    unsigned long n_send = count, n_recv = 0;
    decomp::send_receive(&n_send, sizeof n_send, to, &n_recv, sizeof n_recv, from, kCountTag, comm, tally);
    std::uint32_t* on_backend = buffer(mirror, slot, n_recv * (record / 4));
    *received = on_backend;
    if (target.direct_mpi) {
        // MPI reads and writes the back end's memory: no staging; the packing must be done.
        exec::synchronize(target);
        decomp::send_receive(packed, count * record, to, on_backend, n_recv * record, from, kDataTag, comm,
                             tally);
        return n_recv;
    }
    void* send = mirror.staging(kStageSend, count * record);
    void* receive = mirror.staging(kStageReceive, n_recv * record);
    // A face without a neighbour (a wall) moves nothing, but every rank takes part.
    if (count > 0) mirror.copy_to_host(send, packed, count * record);
    decomp::send_receive(send, count * record, to, receive, n_recv * record, from, kDataTag, comm, tally);
    if (n_recv > 0) mirror.copy_to_backend(on_backend, receive, n_recv * record);
    return n_recv;
}

void BackendListBuild::migrate(const exec::Target& target, exec::ParticleMirror& mirror,
                               ParticleStore& store, const decomp::RankGrid& grid) {
    const Vec3 lo = grid.lo(), hi = grid.hi(), len = grid.global().length();
    const Wedge& wedge = grid.global().wedge;
    if (wedge.active())
        exec::for_each(target, store.n_owned(),
                       build::TurnIntoWedge{mirror.array<Vec3>(kPosition), mirror.array<Vec3>(kVelocity), wedge});
    const unsigned words = packed_words(mirror);
    for (int d = 0; d < 3; ++d) {
        const std::size_t n = store.n_owned();
        std::uint32_t* leave[2] = {buffer(mirror, kFlags, n + 1), buffer(mirror, kLeave1, n + 1)};
        int* fault = reinterpret_cast<int*>(buffer(mirror, kFaults, n));
        build::LeaveAlong along{mirror.array<Vec3>(kPosition), mirror.array<Int3>(kImage), d, lo[d], hi[d],
                                len[d], {0, 0}, {0, 0}, grid.dims()[d] == 1, n, leave[0], leave[1], fault};
        for (int side = 0; side < 2; ++side) {
            along.open[side] = grid.neighbour(d, side) != MPI_PROC_NULL;
            along.wraps[side] = along.open[side] && grid.wraps(d, side);
        }
        exec::for_each(target, n + 1, along);
        describe_fault(target, mirror, n, fault, d);
        if (along.alone) continue;  // the wrap was the whole move
        // Who leaves through each side, who stays; the leavers packed before the stayers
        // close ranks.
        std::size_t count[2];
        const int* index[2];
        std::uint32_t* packed[2];
        for (int side = 0; side < 2; ++side) {
            count[side] = exec::exclusive_scan(target, leave[side], leave[side], n + 1);
            int* list = reinterpret_cast<int*>(buffer(mirror, side == 0 ? kIndex0 : kIndex1, count[side]));
            exec::for_each(target, n, build::Compact{leave[side], list});
            index[side] = list;
        }
        std::uint32_t* keep = buffer(mirror, kKeep, n + 1);
        exec::for_each(target, n + 1, build::Stays{leave[0], leave[1], n, keep});
        const std::size_t n_keep = exec::exclusive_scan(target, keep, keep, n + 1);
        int* kept = reinterpret_cast<int*>(buffer(mirror, kValues, n_keep));
        exec::for_each(target, n, build::Compact{keep, kept});
        std::uint32_t* send = buffer(mirror, kSend, (count[0] + count[1]) * words);
        packed[0] = send;
        packed[1] = send + count[0] * words;
        for (int side = 0; side < 2; ++side)
            pack(target, mirror, index[side], count[side], packed[side], false, Vec3{0, 0, 0}, 0, wedge);
        gather_owned(target, mirror, store, kept, n_keep);
        for (int side = 0; side < 2; ++side) {
            const std::uint32_t* received = nullptr;
            const std::size_t n_recv = exchange(target, mirror, grid.comm(), grid.neighbour(d, side),
                                                grid.neighbour(d, 1 - side), packed[side], count[side],
                                                kReceive, &received, migration_traffic_);
            const std::size_t first = store.n_owned();
            mirror.resize_on_backend(store, first + n_recv, 0);
            unpack(mirror, received, n_recv, first);
            if (fault_.empty() && n_recv > 0) {
                const std::size_t k = exec::first_index(
                    target, n_recv, build::ArrivedOutside{mirror.array<Vec3>(kPosition), d, lo[d], hi[d], first});
                if (k < n_recv) name_fault(target, mirror, first + k, d, decomp::kMovedMoreThanADomain);
            }
        }
    }
}

void BackendListBuild::drop_constituents(const exec::Target& target, exec::ParticleMirror& mirror,
                                         ParticleStore& store) {
    const std::size_t n = store.n_owned();
    std::uint32_t* keep = buffer(mirror, kKeep, n + 1);
    exec::for_each(target, n + 1, build::IsFree{mirror.array<std::int64_t>(kBody), n, keep});
    n_free_ = exec::exclusive_scan(target, keep, keep, n + 1);
    int* kept = reinterpret_cast<int*>(buffer(mirror, kValues, n_free_));
    exec::for_each(target, n, build::Compact{keep, kept});
    gather_owned(target, mirror, store, kept, n_free_);
}

void BackendListBuild::gather_owned(const exec::Target& target, exec::ParticleMirror& mirror, ParticleStore& store,
                                    const int* index, std::size_t count) {
    std::uint32_t* moved = buffer(mirror, kGather, count * packed_words(mirror));
    pack(target, mirror, index, count, moved, false, Vec3{0, 0, 0}, 0, Wedge{});
    unpack(mirror, moved, count, 0);
    mirror.resize_on_backend(store, count, 0);
}

void BackendListBuild::append_constituents(const exec::Target& target, exec::ParticleMirror& mirror,
                                           ParticleStore& store, const Bodies& bodies) {
    exec::ParticleMirror& b = *bodies.mirror;
    const std::size_t n_bodies = bodies.store->n_owned();
    const int* kind = b.array<int>(kSpecies);
    std::uint32_t* first = buffer(mirror, kConstituentFirst, n_bodies + 1);
    exec::for_each(target, n_bodies + 1, build::ConstituentCount{kind, bodies.frames.first, n_bodies, first});
    const std::size_t n_constituents = exec::exclusive_scan(target, first, first, n_bodies + 1);
    constituents_.first = first;
    // Constituents at the slots after the free particles, body after body.
    mirror.resize_on_backend(store, n_free_ + n_constituents, 0);
    std::uint32_t* slots = buffer(mirror, kConstituentIndex, n_constituents);
    exec::for_each(target, n_constituents, build::AppendSlots{static_cast<std::uint32_t>(n_free_), slots});
    rigid::RigidBodies::Arrays a;
    a.state = {b.array<Vec3>(kPosition), b.array<Vec3>(kVelocity), b.array<Vec3>(kForce),
               b.array<Quat>(kOrientation), b.array<Quat>(kAngularMomentum), b.array<Vec3>(kTorque), kind};
    a.frames = bodies.frames;
    bodies.rigid->place_at(target, a, rigid::ConstituentIndex{first, slots}, mirror.array<Vec3>(kPosition),
                           mirror.array<Vec3>(kVelocity));
    exec::for_each(target, n_bodies,
                   build::ConstituentFields{kind, b.array<std::int64_t>(kId), b.array<std::int64_t>(kBody),
                                            b.array<Int3>(kImage), bodies.frames.first, bodies.species,
                                            bodies.diameters, first, n_free_, mirror.array<int>(kSpecies),
                                            mirror.array<std::int64_t>(kId), mirror.array<std::int64_t>(kBody),
                                            mirror.array<Int3>(kImage),
                                            store.has_diameters() ? mirror.array<Real>(kDiameter) : nullptr,
                                            mirror.array<Quat>(kOrientation), mirror.array<Quat>(kAngularMomentum),
                                            mirror.array<Vec3>(kTorque)});
}

const std::uint32_t* BackendListBuild::sort_by_cell_and_id(const exec::Target& target, exec::ParticleMirror& mirror,
                                                           ParticleStore& store, const CellList& cells, int id_bits) {
    // By id, then stably by cell: the host's order (cells, ids ascending within each).
    const std::size_t n = store.n_owned();
    std::uint32_t* keys = buffer(mirror, kKeys, n);
    std::uint32_t* order = buffer(mirror, kValues, n);
    exec::for_each(target, n, build::IdKey{mirror.array<std::int64_t>(kId), keys, order});
    exec::sort_pairs(target, keys, order, n, id_bits);
    exec::for_each(target, n, build::CellKey{mirror.array<Vec3>(kPosition), cells.index(), keys, order, false});
    exec::sort_pairs(target, keys, order, n, key_bits(static_cast<std::size_t>(cells.n_cells())));
    // Every array but the forces (recomputed after a build) takes the new order.
    gather_owned(target, mirror, store, reinterpret_cast<const int*>(order), n);
    return order;
}

/// The back end's particles as decomp::make_halo_plan() sees them: exports flagged by position
/// and compacted (kept for refreshes), copies made in place where the swap is this rank's own,
/// else packed, staged and exchanged, ghosts appended.
struct BackendListBuild::BackendPlace {
    BackendListBuild& build;
    const exec::Target& target;
    exec::ParticleMirror& mirror;
    ParticleStore& store;
    const decomp::RankGrid& grid;
    double width;

    std::size_t size() const { return store.size(); }

    std::size_t select(const decomp::SwapRoute& route, std::size_t k, std::size_t n_candidates) {
        const Wedge& wedge = grid.global().wedge;
        const int d = route.axis, side = route.side;
        build::NearFace near{mirror.array<Vec3>(kPosition), d, side, 0, wedge, 0, 0, nullptr};
        if (d < 0) {
            near.width = width;  // a wedge's cut face
        } else {
            // A face without a neighbour exports nothing: its flags are all 0.
            const bool open = route.send_rank != MPI_PROC_NULL;
            near.edge = !open ? (side == 0 ? -INFINITY : INFINITY)
                              : (side == 0 ? grid.lo()[d] + width : grid.hi()[d] - width);
        }
        std::uint32_t* flag = build.buffer(mirror, kFlags, n_candidates + 1);
        near.flag = flag;
        near.n = n_candidates;
        exec::for_each(target, n_candidates + 1, near);
        const std::size_t count = exec::exclusive_scan(target, flag, flag, n_candidates + 1);
        int* index = reinterpret_cast<int*>(build.buffer(mirror, kSwapIndex0 + k, count));
        exec::for_each(target, n_candidates, build::Compact{flag, index});
        build.swap_index_.push_back(index);
        build.swap_count_.push_back(count);
        return count;
    }

    std::size_t move(const decomp::SwapRoute& route, std::size_t k, std::size_t count) {
        const Wedge& wedge = grid.global().wedge;
        const int* index = build.swap_index_.at(k);
        const std::size_t import_first = store.size();
        if (route.to_self) {
            // The owners' values of every field (ghosts carry what owners have), positions moved
            // to the image and velocities turned, as HaloExchange does; in place, since every
            // source lies before the new ghosts.
            mirror.resize_on_backend(store, store.n_owned(), store.n_ghost() + count);
            build::FieldGather copies;
            mirror.for_each_array([&](FieldMask field, std::size_t bytes, void* data) {
                if (field == kForce || field == kPosition || (route.turns && field == kVelocity)) return;
                const unsigned words = static_cast<unsigned>(bytes / 4);
                std::uint32_t* a = static_cast<std::uint32_t*>(data);
                add_field(copies, a, a + import_first * words, words);
            });
            Vec3* x = mirror.array<Vec3>(kPosition);
            Vec3* v = mirror.array<Vec3>(kVelocity);
            exec::for_each(target, count,
                           build::GatherImages{{copies, index},
                                               {x, index, x + import_first, wedge, route.turns, route.shift},
                                               {v, index, v + import_first, wedge, route.turns}});
            return count;
        }
        std::uint32_t* packed = build.buffer(mirror, kSend, count * build.packed_words(mirror));
        build.pack(target, mirror, index, count, packed, true, route.shift, route.turns, wedge);
        const std::uint32_t* received = nullptr;
        const std::size_t n_recv = build.exchange(target, mirror, grid.comm(), route.send_rank, route.recv_rank,
                                                  packed, count, kReceive, &received, build.ghost_traffic_);
        mirror.resize_on_backend(store, store.n_owned(), store.n_ghost() + n_recv);
        build.unpack(mirror, received, n_recv, import_first);
        return n_recv;
    }
};

void BackendListBuild::make_ghosts(const exec::Target& target, exec::ParticleMirror& mirror,
                                   ParticleStore& store, const decomp::RankGrid& grid, double width,
                                   decomp::HaloExchange& halo, exec::BackendHalo& backend_halo) {
    if (one_domain(grid)) {
        make_images(target, mirror, store, grid, width, halo, backend_halo, nullptr);
        return;
    }
    swap_index_.clear();
    swap_count_.clear();
    BackendPlace place{*this, target, mirror, store, grid, width};
    halo.adopt_plan(grid, decomp::make_halo_plan(grid, place));
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
    exec::sort_pairs(target, keys, member, n, key_bits(n_cells));
    std::uint32_t* start = buffer(mirror, kCellStart, n_cells + 1);
    exec::for_each(target, n_cells + 1, build::CellStart{keys, n, start});
    // Count, scan to offsets, list.
    const std::int64_t* body = store.has_rigid_fields() ? mirror.array<std::int64_t>(kBody) : nullptr;
    std::uint32_t* offset = buffer(mirror, kOffsets, n_owned + 1);
    build::ListNeighbours search{x, body, grid, start, member, list_range * list_range, n_owned, nullptr, offset};
    if (range_table_) {
        search.range_table = range_table_;
        search.species = mirror.array<int>(kSpecies);
        search.n_species = static_cast<unsigned>(n_range_species_);
        search.short_reach =
            exec::transform_max(target, n, 0.0, build::SpeciesOutside{search.species, n_range_species_}) == 0.0;
    }
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

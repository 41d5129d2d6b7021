// SPDX-License-Identifier: MIT
// The list build where the particles live: migration, the cell order, ghosts, cells and the
// full Verlet list, all as loops through the execution layer on the back end's arrays (with
// rigid bodies: their constituents dropped, the bodies migrated whole and their constituents
// placed again, as RigidBodies does on the host), so on one rank a build moves no particle
// array between host and device (only counts come back); with several ranks what crosses a
// domain face, particles and bodies alike, is packed there and staged through host memory for
// MPI. It gives the host build's particle order, ghosts and list bit for bit
// (list_build_loops.hpp), so a run continues the same whichever builds. It covers free
// particles and rigid bodies in periodic, walled and wedge regions on any rank count.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "decomposition/halo_exchange.hpp"
#include "decomposition/rank_grid.hpp"
#include "emergent/execution.hpp"
#include "emergent/particle_store.hpp"
#include "neighbour/backend_halo.hpp"
#include "particles/particle_mirror.hpp"
#include "neighbour/cell_list.hpp"
#include "neighbour/list_build_loops.hpp"
#include "rigid/body_motion.hpp"
#include "rigid/rigid_bodies.hpp"

namespace emergent {
namespace build {
struct FieldGather;
}

class BackendListBuild {
public:
    /// The bodies' side of a build with rigid bodies: their arrays (a second mirror of their
    /// store) and their kinds' tables on the back end (frames; constituent species and
    /// diameters aligned with the frame positions).
    struct Bodies {
        const rigid::RigidBodies* rigid = nullptr;  ///< places the constituents
        exec::ParticleMirror* mirror = nullptr;
        ParticleStore* store = nullptr;
        rigid::FrameTable frames{};
        const int* species = nullptr;
        const double* diameters = nullptr;
        unsigned fields = 0;  ///< the fields the engine keeps of bodies (stale on the host after a migration)
    };

    /// Builds on the back end. Every field but forces must be current there or on the host
    /// (the mirror uploads what is stale); afterwards all live on the back end, the store holds
    /// the new size, `halo` and `backend_halo` the ghost plan. Collective. Returns false on
    /// every rank where some id does not fit the sort keys (the caller builds on the host):
    /// having changed nothing, or (one domain) having brought the particles home and sorted
    /// them, which the host's build repeats to the same end; returns true with fault() set on every rank where some particle
    /// could not be brought home (the caller stops).
    bool build(const exec::Target& target, exec::ParticleMirror& mirror, ParticleStore& store,
               const decomp::RankGrid& grid, const CellList& cells, double ghost_width,
               double list_range, decomp::HaloExchange& halo, exec::BackendHalo& backend_halo,
               const Bodies* bodies = nullptr);

    /// Ranges by species for the builds that follow (NeighbourList::range_table of n species,
    /// already on the back end); null: every pair within the list range.
    void set_pair_ranges(const double* range_table_on_backend, int n_species) {
        range_table_ = range_table_on_backend;
        n_range_species_ = range_table_on_backend ? n_species : 0;
    }

    /// The first particle that could not be brought home (of the first rank with one),
    /// described as the host's migration does; empty if none.
    const std::string& fault() const { return fault_; }
    /// What this rank sent to others in builds since it was made: migration, ghosts.
    const MessageCounts& migration_traffic() const { return migration_traffic_; }
    const MessageCounts& ghost_traffic() const { return ghost_traffic_; }
    /// Wall seconds the migrations of particles and bodies took since the last call.
    double take_migration_seconds() {
        const double s = migration_seconds_;
        migration_seconds_ = 0;
        return s;
    }
    /// The full list on the back end (CSR: neighbours of i are index[offset[i] .. offset[i+1])).
    const std::uint32_t* offsets() const { return offsets_; }
    const std::uint32_t* neighbours() const { return neighbours_; }
    std::size_t n_pairs() const { return n_pairs_; }
    /// Owned positions at the build, on the back end.
    const Vec3* reference() const { return reference_; }
    /// With bodies: where each body's constituents sit now (rigid::ConstituentIndex), on the
    /// back end.
    rigid::ConstituentIndex constituents() const { return constituents_; }

    /// The scratch slots of the mirror this build uses, from `first` on (the engine's others
    /// lie below).
    explicit BackendListBuild(std::size_t first_slot = 16) : slot_(first_slot) {}

private:
    /// Migration on one rank, in one pass; fault_ set where a particle cannot come home.
    void come_home(const exec::Target& target, exec::ParticleMirror& mirror, ParticleStore& store,
                   const decomp::RankGrid& grid);
    /// Migration on a decomposed grid, axis by axis as decomp::Migration; fault_ set (on this
    /// rank) as there.
    void migrate(const exec::Target& target, exec::ParticleMirror& mirror, ParticleStore& store,
                 const decomp::RankGrid& grid);
    /// Names the first particle with the first fault among the first n, in fault_ (unless a
    /// fault was named already). Codes as LeaveAlong's on axis `axis`, or with axis -1 as
    /// ComeHome's (all axes).
    void describe_fault(const exec::Target& target, exec::ParticleMirror& mirror, std::size_t n,
                        const int* fault, int axis);
    /// Names particle i (its id and position on the back end) in fault_, as the host would.
    /// Names particle i by its fault code (as describe_fault reads codes: per axis, or with
    /// axis -1 a one-pass migration's).
    void name_fault_code(const exec::Target& target, const exec::ParticleMirror& mirror, std::size_t i, int code,
                         int axis);
    void name_fault(const exec::Target& target, const exec::ParticleMirror& mirror, std::size_t i, int axis,
                    const char* why);
    /// The owned particles become index[0 .. count) in that order, every array but the forces
    /// (the store holds count owned particles after).
    void gather_owned(const exec::Target& target, exec::ParticleMirror& mirror, ParticleStore& store,
                      const int* index, std::size_t count);
    /// Every array but the forces of particles index[0 .. count), field block after field
    /// block, into `out` (on the back end); positions as images (shifted, turned) where
    /// `image`, velocities turned.
    static void add_field(build::FieldGather& gather, const std::uint32_t* from, std::uint32_t* to,
                          unsigned words);
    void pack(const exec::Target& target, exec::ParticleMirror& mirror, const int* index,
              std::size_t count, std::uint32_t* out, bool image, const Vec3& shift, int turns,
              const Wedge& wedge);
    /// The inverse: `count` packed particles into slots [first, first + count).
    void unpack(exec::ParticleMirror& mirror, const std::uint32_t* in, std::size_t count, std::size_t first);
    /// Sends `count` packed particles (on the back end) to rank `to` and receives from
    /// `from` into the back end's buffer `slot`, staged through host memory (or directly where
    /// MPI reads device memory); returns how many came, *received where.
    std::size_t exchange(const exec::Target& target, exec::ParticleMirror& mirror, MPI_Comm comm, int to, int from,
                         const std::uint32_t* packed, std::size_t count, std::size_t slot,
                         const std::uint32_t** received, MessageCounts& tally);
    /// 32-bit words per particle of every array but the forces.
    unsigned packed_words(const exec::ParticleMirror& mirror) const;
    /// Drops the constituents of bodies (free particles close ranks, in order).
    void drop_constituents(const exec::Target& target, exec::ParticleMirror& mirror, ParticleStore& store);
    /// Appends the bodies' constituents after the free particles, in body order.
    void append_constituents(const exec::Target& target, exec::ParticleMirror& mirror, ParticleStore& store,
                             const Bodies& bodies);
    /// Sorts by cell and id; returns the order (order[k] = old index of new k), on the back end.
    const std::uint32_t* sort_by_cell_and_id(const exec::Target& target, exec::ParticleMirror& mirror,
                                             ParticleStore& store, const CellList& cells, int id_bits);
    void make_ghosts(const exec::Target& target, exec::ParticleMirror& mirror, ParticleStore& store,
                     const decomp::RankGrid& grid, double width, decomp::HaloExchange& halo,
                     exec::BackendHalo& backend_halo);
    /// Whether the domain is alone (decomp::lone_domain: one rank, no wedge): then one pass
    /// brings particles home and keys them, one sort orders them, and every ghost is made from
    /// its owner in one pass (make_images).
    static bool one_domain(const decomp::RankGrid& grid) { return decomp::lone_domain(grid); }
    /// The build of one domain without bodies: 12 passes over particles, 2 read-backs (the
    /// images' counts with the migration's faults, the list's length).
    bool build_one_domain(const exec::Target& target, exec::ParticleMirror& mirror, ParticleStore& store,
                          const decomp::RankGrid& grid, const CellList& cells, double ghost_width,
                          double list_range, decomp::HaloExchange& halo, exec::BackendHalo& backend_halo);
    /// One domain's ghosts, every kind of image at once (decomp::LoneDomainImages): a pass counting
    /// them (which reads back, with the counts, the faults of the migration before it, from
    /// `fault` where given), a scan, a pass writing them with their roots; the halo's plan and
    /// the refreshes' roots placed. Writes nothing where a fault or an id outside the keys was
    /// found (returned).
    build::ImageCounts make_images(const exec::Target& target, exec::ParticleMirror& mirror, ParticleStore& store,
                                   const decomp::RankGrid& grid, double width, decomp::HaloExchange& halo,
                                   exec::BackendHalo& backend_halo, const int* fault);
    /// What decomp::make_halo_plan() needs from the back end's particles (make_ghosts).
    struct BackendPlace;
    void list(const exec::Target& target, exec::ParticleMirror& mirror, const ParticleStore& store,
              const CellList& cells, double list_range);

    std::uint32_t* buffer(exec::ParticleMirror& mirror, std::size_t which, std::size_t count) {
        return static_cast<std::uint32_t*>(mirror.scratch(slot_ + which, count * sizeof(std::uint32_t)));
    }
    enum Buffer : std::size_t { kKeys, kValues, kFlags, kGather, kCellStart, kOffsets, kNeighbours,
                                kReference, kFaults, kLeave1, kKeep, kSend, kReceive, kIndex0, kIndex1,
                                kConstituentFirst, kConstituentIndex, kNewOfOld,
                                kSwapIndex0,  // then one per swap (up to 8)
                                kRoots = kSwapIndex0 + 8, kShifts };

    std::size_t slot_;
    const double* range_table_ = nullptr;
    int n_range_species_ = 0;
    std::string fault_;
    const std::uint32_t *offsets_ = nullptr, *neighbours_ = nullptr;
    std::size_t n_pairs_ = 0;
    const Vec3* reference_ = nullptr;
    rigid::ConstituentIndex constituents_{};
    MessageCounts migration_traffic_, ghost_traffic_;
    double migration_seconds_ = 0;
    std::size_t n_free_ = 0;  ///< free particles before the constituents, at the last build
    std::vector<const int*> swap_index_;
    std::vector<std::size_t> swap_count_;
};

}  // namespace emergent

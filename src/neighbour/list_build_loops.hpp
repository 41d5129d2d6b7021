// SPDX-License-Identifier: MIT
// The per-particle loops of a list build where the particles live (BackendListBuild): bring
// particles home across periodic and wedge boundaries, order them by cell and id, make their
// ghost images, bin and list. Each loop gives the host build's result bit for bit (the same
// order, the same images, the same list), so the back end and the host agree exactly.
#pragma once

#include <cstddef>
#include <cstdint>

#include "decomposition/ghost_image.hpp"
#include "emergent/box.hpp"
#include "emergent/quaternion.hpp"
#include "emergent/vec3.hpp"
#include "neighbour/cell_list.hpp"
#include "rigid/body_motion.hpp"

namespace emergent::build {

/// Bits of the largest of n sort keys 0 .. n - 1 (at least 1): a radix sort's passes.
inline int key_bits(std::size_t n) {
    int bits = 1;
    while (bits < 32 && (std::size_t{1} << bits) < n) ++bits;
    return bits;
}

/// What stopped a particle from coming home (fault codes; 0: none), ordered as the host's
/// migration finds them: axis by axis; on an axis, closed faces first (by index), then long
/// jumps through side 0, then through side 1 (each by index). So the smallest code, and the
/// smallest index with it, is the particle the host reports.
EMERGENT_HD inline int fault_code(int axis, bool closed_face, int side) {
    return 1 + 3 * axis + (closed_face ? 0 : 1 + side);
}

/// One rank's migration: a particle past a cut face of a wedge comes back turned; one past a
/// periodic face wraps (its image count follows); one past a closed face is a fault, as is one
/// still outside after wrapping (it jumped more than a box length). fault[i] is the fault's
/// code, 0 if none; a particle with a fault stays where it was found (the run stops).
struct ComeHome {
    Vec3* x;
    Vec3* v;
    Int3* image;
    Wedge wedge;
    Vec3 lo, hi, length;
    int periodic[3];  ///< 1 where the axis wraps (its faces have this rank behind them)
    int* fault;
    EMERGENT_HD void operator()(std::size_t i) const {
        if (wedge.active()) {
            const int turns = wedge.turns_into(x[i]);
            if (turns) {
                x[i] = wedge.rotate(x[i], turns);
                v[i] = wedge.rotate(v[i], turns);
            }
        }
        fault[i] = 0;
        for (int d = 0; d < 3; ++d) {
            const int side = x[i][d] < lo[d] ? 0 : (x[i][d] >= hi[d] ? 1 : -1);
            if (side < 0) continue;
            if (!periodic[d]) {
                fault[i] = fault_code(d, true, side);
                return;
            }
            x[i][d] += side == 0 ? length[d] : -length[d];
            image[i][d] += side == 0 ? -1 : 1;
            if (x[i][d] < lo[d] || x[i][d] >= hi[d]) {
                fault[i] = fault_code(d, false, side);
                return;
            }
        }
    }
};

/// A particle past a cut face of a wedge comes back in through the other, turned: the first
/// part of migration on a decomposed grid (x and y are whole on every rank).
struct TurnIntoWedge {
    Vec3* x;
    Vec3* v;
    Wedge wedge;
    EMERGENT_HD void operator()(std::size_t i) const {
        const int turns = wedge.turns_into(x[i]);
        if (turns) {
            x[i] = wedge.rotate(x[i], turns);
            v[i] = wedge.rotate(v[i], turns);
        }
    }
};

/// Migration along one axis of a decomposed grid, as decomp::Migration: a particle past a face
/// with a rank behind it wraps where the face is periodic and leaves through that side
/// (leave0/leave1 flags, each ending in 0 at n for the scans); one past a closed face stays
/// (fault 1). With one rank along the axis the wrap is the whole move, and a particle still
/// outside jumped more than a box length (fault 2 through side 0, 3 through side 1).
struct LeaveAlong {
    Vec3* x;
    Int3* image;
    int axis;
    Real lo, hi, length;
    int open[2], wraps[2];
    bool alone;
    std::size_t n;
    std::uint32_t* leave0;
    std::uint32_t* leave1;
    int* fault;
    EMERGENT_HD void operator()(std::size_t i) const {
        if (i == n) {
            leave0[i] = leave1[i] = 0;
            return;
        }
        leave0[i] = leave1[i] = 0;
        fault[i] = 0;
        Real& c = x[i][axis];
        const int side = c < lo ? 0 : (c >= hi ? 1 : -1);
        if (side < 0) return;
        if (!open[side]) {
            fault[i] = 1;
            return;
        }
        if (wraps[side]) {
            c += side == 0 ? length : -length;
            image[i][axis] += side == 0 ? -1 : 1;
        }
        if (alone) {
            if (c < lo || c >= hi) fault[i] = 2 + side;
            return;
        }
        (side == 0 ? leave0 : leave1)[i] = 1;
    }
};

/// After the scans of both sides' leave flags (slot0, slot1): keep[i] = 1 where particle i
/// stays, keep[n] = 0.
struct Stays {
    const std::uint32_t* slot0;
    const std::uint32_t* slot1;
    std::size_t n;
    std::uint32_t* keep;
    EMERGENT_HD void operator()(std::size_t i) const {
        keep[i] = i < n && slot0[i + 1] == slot0[i] && slot1[i + 1] == slot1[i] ? 1u : 0u;
    }
};

/// A particle that arrived at slot first + k lies outside the domain along the axis: it moved
/// more than one domain between list builds.
struct ArrivedOutside {
    const Vec3* x;
    int axis;
    Real lo, hi;
    std::size_t first;
    EMERGENT_HD bool operator()(std::size_t k) const {
        const Real c = x[first + k][axis];
        return c < lo || c >= hi;
    }
};

/// keep[i] = 1 for a free particle (body < 0), 0 for a constituent of a body; keep[n] = 0.
struct IsFree {
    const std::int64_t* body;
    std::size_t n;
    std::uint32_t* keep;
    EMERGENT_HD void operator()(std::size_t i) const { keep[i] = i < n && body[i] < 0 ? 1u : 0u; }
};

/// count[b] = constituents of body b (its kind's frame), count[n] = 0: scanned, where each
/// body's constituents begin.
struct ConstituentCount {
    const int* kind;
    const std::uint32_t* frame_first;
    std::size_t n;
    std::uint32_t* count;
    EMERGENT_HD void operator()(std::size_t b) const {
        count[b] = b < n ? frame_first[kind[b] + 1] - frame_first[kind[b]] : 0u;
    }
};

/// index[j] = first + j: the slots the constituents are appended at.
struct AppendSlots {
    std::uint32_t first;
    std::uint32_t* index;
    EMERGENT_HD void operator()(std::size_t j) const { index[j] = first + static_cast<std::uint32_t>(j); }
};

/// Constituent k of body b, appended at slot `at`: its fields other than position and velocity,
/// as RigidBodies::append_constituents gives them (id first constituent id + k, the body's id
/// and image, its kind's species and diameter; orientation, angular momentum and torque at their
/// fill values).
struct ConstituentFields {
    const int* kind;
    const std::int64_t* body_id;
    const std::int64_t* first_id;
    const Int3* body_image;
    const std::uint32_t* frame_first;
    const int* frame_species;
    const double* frame_diameter;
    const std::uint32_t* first;  ///< where body b's constituents begin (scanned counts)
    std::size_t at;              ///< the first constituent's slot
    int* species;
    std::int64_t* id;
    std::int64_t* body;
    Int3* image;
    Real* diameter;  ///< null: the store has none
    Quat* orientation;
    Quat* angular_momentum;
    Vec3* torque;
    EMERGENT_HD void operator()(std::size_t b) const {
        const int k = kind[b];
        for (std::uint32_t j = 0; j < frame_first[k + 1] - frame_first[k]; ++j) {
            const std::size_t i = at + first[b] + j;
            species[i] = frame_species[frame_first[k] + j];
            id[i] = first_id[b] + static_cast<std::int64_t>(j);
            body[i] = body_id[b];
            image[i] = body_image[b];
            if (diameter) diameter[i] = frame_diameter[frame_first[k] + j];
            orientation[i] = Quat{};
            angular_momentum[i] = Quat{0, 0, 0, 0};
            torque[i] = Vec3{0, 0, 0};
        }
    }
};

/// new_of_old[order[k]] = k: where each particle went in a new order.
struct InvertOrder {
    const std::uint32_t* order;
    std::uint32_t* new_of_old;
    EMERGENT_HD void operator()(std::size_t k) const { new_of_old[order[k]] = static_cast<std::uint32_t>(k); }
};

/// index[j] = new_of_old[at + j]: the constituent index after the sort.
struct MovedSlots {
    const std::uint32_t* new_of_old;
    std::size_t at;
    std::uint32_t* index;
    EMERGENT_HD void operator()(std::size_t j) const { index[j] = new_of_old[at + j]; }
};

/// -fault[i], or -infinity where there is none: the largest is minus the first fault's code.
struct FaultOrder {
    const int* fault;
    EMERGENT_HD double operator()(std::size_t i) const { return fault[i] ? -double(fault[i]) : -1e300; }
};

/// fault[i] == code: the first particle with a given fault.
struct HasFault {
    const int* fault;
    int code;
    EMERGENT_HD bool operator()(std::size_t i) const { return fault[i] == code; }
};

/// An id as a sort key's magnitude (a negative id counts as too large for the keys).
struct IdMagnitude {
    const std::int64_t* id;
    EMERGENT_HD double operator()(std::size_t i) const { return id[i] < 0 ? 1e300 : double(id[i]); }
};

/// key[i] = id[i] (ids below 2^32), value[i] = i: the first sort, by id.
struct IdKey {
    const std::int64_t* id;
    std::uint32_t* key;
    std::uint32_t* value;
    EMERGENT_HD void operator()(std::size_t i) const {
        key[i] = static_cast<std::uint32_t>(id[i]);
        value[i] = static_cast<std::uint32_t>(i);
    }
};

/// key[k] = cell of particle value[k] (or of k itself where value is null, value[k] set to k):
/// the second, stable, sort then orders by cell, and by the first sort's key within a cell.
struct CellKey {
    const Vec3* x;
    CellIndex cells;
    std::uint32_t* key;
    std::uint32_t* value;
    bool identity;
    EMERGENT_HD void operator()(std::size_t k) const {
        if (identity) value[k] = static_cast<std::uint32_t>(k);
        key[k] = static_cast<std::uint32_t>(cells.cell_of(x[value[k]]));
    }
};

/// The particle arrays to move alike (GatherFields): each as 32-bit words, `words` per
/// particle, whatever the field holds.
struct FieldGather {
    static constexpr int kMaxFields = 11;  ///< every FieldMask bit
    const std::uint32_t* from[kMaxFields];
    std::uint32_t* to[kMaxFields];
    unsigned words[kMaxFields];
    int n_fields = 0;
    /// Adds a field: `words` 32-bit words per particle. False where the table is full.
    bool add(const std::uint32_t* a, std::uint32_t* b, unsigned w) {
        if (n_fields == kMaxFields) return false;
        from[n_fields] = a, to[n_fields] = b, words[n_fields] = w;
        ++n_fields;
        return true;
    }
};

/// to_f[k] = from_f[order[k]] for every field f of the table: the arrays moved into a new order,
/// or ghosts copied from their owners (to past the owners), in one pass (the order read once;
/// one launch on a device, not one per field).
template <class Index>
struct GatherFields {
    FieldGather fields;
    const Index* order;
    EMERGENT_HD void operator()(std::size_t k) const {
        const std::size_t i = static_cast<std::size_t>(order[k]);
        for (int f = 0; f < fields.n_fields; ++f) {
            const unsigned words = fields.words[f];
            const std::uint32_t* a = fields.from[f] + i * words;
            std::uint32_t* b = fields.to[f] + k * words;
            for (unsigned w = 0; w < words; ++w) b[w] = a[w];
        }
    }
};

/// ComeHome's fault code for an id that no sort key holds (negative, or 2^32 or more): the
/// build is left to the host.
constexpr int kIdOutsideKeys = 1 << 20;

/// One rank's migration (ComeHome) and the sort key of where it leaves the particle, in one
/// pass: key[i] = cell << 32 | id (one sort orders by cell, and by id within a cell: the
/// host's order), value[i] = i. A particle with a fault keys into the nearest cell, so that the
/// build goes on safely to where the fault is read (with the ghosts' counts); one with an id
/// no key holds is marked kIdOutsideKeys.
struct ComeHomeAndKey {
    ComeHome home;
    const std::int64_t* id;
    CellIndex cells;
    std::uint64_t* key;
    std::uint32_t* value;
    EMERGENT_HD void operator()(std::size_t i) const {
        home(i);
        int c = cells.cell_of(home.x[i]);
        const int n_cells = cells.n.x * cells.n.y * cells.n.z;
        c = c < 0 ? 0 : (c >= n_cells ? n_cells - 1 : c);
        const std::int64_t d = id[i];
        if (d < 0 || d > std::int64_t{0xffffffff}) home.fault[i] = kIdOutsideKeys;
        key[i] = (static_cast<std::uint64_t>(c) << 32) | static_cast<std::uint32_t>(d);
        value[i] = static_cast<std::uint32_t>(i);
    }
};

/// The most kinds of periodic image one domain gives its particles: 3^3 - 1 (faces, edges,
/// corners).
constexpr int kMaxImageKinds = 26;
/// Particles per block of the images' counts: a kind's count is kept per block, and a particle
/// finds its rank within its block by looking at the block's earlier members (so the counts take
/// 4 bytes per kind and block, not per kind and particle).
constexpr std::size_t kImageBlock = 32;

/// The kinds of image of a domain that is its own neighbour on every open face (one rank, no
/// wedge), in the order the halo's swaps make them (decomp::LoneDomainImages): kind q is made from a particle near every face whose bit is
/// in need[q] (bit 2 d + side: face (d, side)), at its position plus shift[q]. Within a kind the
/// images follow their owners' order, so the ghost slot of (kind q, particle i) is the count of
/// images of kinds before q plus those of kind q from particles before i: the swaps' order.
struct ImageKinds {
    int n = 0;
    unsigned need[kMaxImageKinds];
    Vec3 shift[kMaxImageKinds];
    Real edge[3][2];  ///< near face (d, 0): x[d] < edge[d][0]; (d, 1): x[d] >= edge[d][1]
    /// The faces x is near, a bit for each (as NearFace decides it).
    EMERGENT_HD unsigned near(const Vec3& x) const {
        unsigned bits = 0;
        for (int d = 0; d < 3; ++d) {
            if (x[d] < edge[d][0]) bits |= 1u << (2 * d);
            if (x[d] >= edge[d][1]) bits |= 2u << (2 * d);
        }
        return bits;
    }
    EMERGENT_HD bool has(unsigned bits, int q) const { return (bits & need[q]) == need[q]; }
};

/// Images counted by kind, with what the migration before found: the first fault (its code
/// above the particle's index: the smallest is the host's first) and whether an id lay outside
/// the keys. A sum of these (transform_sum) is the counts' sum, the faults' minimum.
struct ImageCounts {
    std::uint32_t count[kMaxImageKinds] = {};
    std::uint64_t first_fault = ~std::uint64_t{0};
    std::uint32_t ids_outside = 0;
    EMERGENT_HD ImageCounts& operator+=(const ImageCounts& o) {
        for (int q = 0; q < kMaxImageKinds; ++q) count[q] += o.count[q];
        first_fault = o.first_fault < first_fault ? o.first_fault : first_fault;
        ids_outside |= o.ids_outside;
        return *this;
    }
};

/// Block b of the owned particles (kImageBlock of them): count[q * (n_blocks + 1) + b] = its
/// images of kind q (0 at b = n_blocks, so one scan over all kinds gives every block its first
/// ghost slot of each kind); returns the block's counts and its fault (fault null: none to
/// report).
struct CountImages {
    const Vec3* x;
    ImageKinds kinds;
    std::size_t n, n_blocks;
    std::uint32_t* count;
    const int* fault;
    EMERGENT_HD ImageCounts operator()(std::size_t b) const {
        ImageCounts c;
        const std::size_t first = b * kImageBlock, last = first + kImageBlock < n ? first + kImageBlock : n;
        for (std::size_t i = first; i < last; ++i) {
            const unsigned bits = kinds.near(x[i]);
            if (bits)
                for (int q = 0; q < kinds.n; ++q) c.count[q] += kinds.has(bits, q) ? 1u : 0u;
            if (fault && fault[i]) {
                if (fault[i] == kIdOutsideKeys)
                    c.ids_outside = 1;
                else if (((static_cast<std::uint64_t>(fault[i]) << 32) | i) < c.first_fault)
                    c.first_fault = (static_cast<std::uint64_t>(fault[i]) << 32) | i;
            }
        }
        for (int q = 0; q < kinds.n; ++q) count[q * (n_blocks + 1) + b] = c.count[q];
        return c;
    }
};

/// After the scan of CountImages' counts (first): owned particle i's images written at their
/// ghost slots n + first of its block and kind + the kind's members before it in the block,
/// every field copied but forces and positions (velocities as they are: no wedge turns them),
/// positions shifted; each ghost's root and total shift kept for the refreshes
/// (decomp::GhostFromRoot): the swaps' images, bit for bit.
struct WriteImages {
    FieldGather fields;  ///< from == to: the store's arrays
    Vec3* x;
    ImageKinds kinds;
    std::size_t n, n_blocks;
    const std::uint32_t* first;
    int* root;
    Vec3* total_shift;
    EMERGENT_HD void operator()(std::size_t i) const {
        const unsigned bits = kinds.near(x[i]);
        if (!bits) return;
        const std::size_t b = i / kImageBlock, start = b * kImageBlock;
        unsigned before[kImageBlock];
        for (std::size_t k = start; k < i; ++k) before[k - start] = kinds.near(x[k]);
        for (int q = 0; q < kinds.n; ++q) {
            if (!kinds.has(bits, q)) continue;
            std::size_t g = first[q * (n_blocks + 1) + b];
            for (std::size_t k = start; k < i; ++k) g += kinds.has(before[k - start], q) ? 1u : 0u;
            const std::size_t j = n + g;
            for (int f = 0; f < fields.n_fields; ++f) {
                const unsigned words = fields.words[f];
                const std::uint32_t* a = fields.from[f] + i * words;
                std::uint32_t* c = fields.to[f] + j * words;
                for (unsigned w = 0; w < words; ++w) c[w] = a[w];
            }
            x[j] = x[i] + kinds.shift[q];
            root[g] = static_cast<int>(i);
            total_shift[g] = kinds.shift[q];
        }
    }
};

/// order[k] == i: where particle i (before a sort) went.
struct WentTo {
    const std::uint32_t* order;
    std::uint32_t i;
    EMERGENT_HD bool operator()(std::size_t k) const { return order[k] == i; }
};

/// flag[i] = 1 where particle i lies within the ghost width of a face, for i < n; flag[n] = 0
/// (the scan that follows then ends in the count). The face: (axis, side) of the domain, or
/// with axis -1 a cut face of the wedge (side 0 theta = 0, side 1 theta = 2 pi / n).
struct NearFace {
    const Vec3* x;
    int axis, side;
    Real edge;  ///< a domain face: lo + width (side 0) or hi - width (side 1)
    Wedge wedge;
    Real width;  ///< a wedge face: the ghost width
    std::size_t n;
    std::uint32_t* flag;
    EMERGENT_HD void operator()(std::size_t i) const {
        if (i == n) {
            flag[i] = 0;
            return;
        }
        bool near;
        if (axis < 0)
            near = (side == 0 ? Wedge::distance_to_first_face(x[i]) : wedge.distance_to_second_face(x[i])) < width;
        else
            near = side == 0 ? x[i][axis] < edge : x[i][axis] >= edge;
        flag[i] = near ? 1u : 0u;
    }
};

/// After an exclusive scan of the flags (slot[i]), the flagged indices in order:
/// out[slot[i]] = i where slot[i + 1] != slot[i].
struct Compact {
    const std::uint32_t* slot;
    int* out;
    EMERGENT_HD void operator()(std::size_t i) const {
        if (slot[i + 1] != slot[i]) out[slot[i]] = static_cast<int>(i);
    }
};

/// A ghost's velocity from its owner's, turned across a wedge face (never shifted, and no
/// zero added: the host's copy). Positions use decomp::GhostImage, as the refreshes do.
struct TurnedCopy {
    const Vec3* in;
    const int* index;
    Vec3* out;
    Wedge wedge;
    int turns;
    EMERGENT_HD void operator()(std::size_t k) const { out[k] = wedge.rotate(in[index[k]], turns); }
};

/// Copies of particles as ghosts, in one pass where three would be: every field as it is but
/// the position, made as its image (decomp::GhostImage: turned, then shifted), and the velocity,
/// turned across a wedge face where velocity.turns is set (else among the fields as it is).
/// Each value the same bits as its own pass would give.
struct GatherImages {
    GatherFields<int> fields;
    decomp::GhostImage position;
    TurnedCopy velocity;
    EMERGENT_HD void operator()(std::size_t k) const {
        fields(k);
        position(k);
        if (velocity.turns) velocity(k);
    }
};

/// start[c] = the first slot of cell c in the keys sorted by cell (n_cells + 1 entries; the
/// last is n): the cells' ranges of members.
struct CellStart {
    const std::uint32_t* key;
    std::size_t n;
    std::uint32_t* start;
    EMERGENT_HD void operator()(std::size_t c) const {
        std::size_t a = 0, b = n;
        while (a < b) {
            const std::size_t m = a + (b - a) / 2;
            if (key[m] < c)
                a = m + 1;
            else
                b = m;
        }
        start[c] = static_cast<std::uint32_t>(a);
    }
};

/// 1 where particle i's species has no row in a table of n species (0 otherwise): with none,
/// searches may stop at their species' range (ListNeighbours::short_reach).
struct SpeciesOutside {
    const int* species;
    int n;
    EMERGENT_HD double operator()(std::size_t i) const { return species[i] < 0 || species[i] >= n ? 1.0 : 0.0; }
};

/// Full list of owned particle i: every j != i (owned or ghost, not of i's body) within the
/// list range (or its species pair's), cells visited z, y, x outermost first and members in
/// index order: the host's NeighbourList::build_full order. Counting pass (offset null):
/// out[i] = the count, and out[n_owned] = 0 for the scan. Listing pass: j's from out[offset[i]] on.
struct ListNeighbours {
    const Vec3* x;
    const std::int64_t* body;  ///< null: no bodies
    CellIndex cells;
    const std::uint32_t* start;
    const std::uint32_t* member;
    Real range_sq;
    std::size_t n_owned;
    const std::uint32_t* offset;
    std::uint32_t* out;
    /// Ranges by species (NeighbourList::range_table, on the back end); null: none.
    /// `short_reach`: every species has its row, so a search stops at its species' range.
    const double* range_table = nullptr;
    const int* species = nullptr;
    unsigned n_species = 0;
    bool short_reach = false;
    EMERGENT_HD void operator()(std::size_t i) const {
        if (i == n_owned) {
            if (!offset) out[i] = 0;
            return;
        }
        const Vec3 xi = x[i];
        const unsigned si = range_table ? static_cast<unsigned>(species[i]) : 0;
        std::uint32_t count = 0;
        auto consider = [&](std::uint32_t j) {
            if (j == i) return;
            if (body && body[i] >= 0 && body[i] == body[j]) return;  // same body
            const Vec3 r = xi - x[j];
            Real limit = range_sq;
            if (range_table) {
                const unsigned sj = static_cast<unsigned>(species[j]);
                if (si < n_species && sj < n_species) limit = Real(range_table[si * n_species + sj]);
            }
            if (dot(r, r) < limit) {
                if (offset) out[offset[i] + count] = j;
                ++count;
            }
        };
        const bool short_search = short_reach && si < n_species;
        cells.visit_within(xi, short_search ? cells.reach_of(range_table[n_species * n_species + si]) : cells.reach,
                           start, member, consider);
        if (!offset) out[i] = count;
    }
};

}  // namespace emergent::build

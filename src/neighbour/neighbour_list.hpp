// SPDX-License-Identifier: MIT
// Verlet neighbour list with a skin, rebuilt only when some particle moved more than skin/2.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <vector>

#include "cell_list.hpp"
#include "emergent/particle_store.hpp"

namespace emergent {

/// |x_i - x0_i|^2: how far particle i moved since the list was built (the rebuild criterion).
struct SquaredDisplacement {
    const Vec3* x;
    const Vec3* x0;
    EMERGENT_HD double operator()(std::size_t i) const {
        const Vec3 r = x[i] - x0[i];
        return dot(r, r);
    }
};

/// Half neighbour list over owned particles: each pair is listed once, under one of its two
/// particles (under the one in the earlier slot: the earlier cell, or earlier in its cell).
/// Every owned–ghost pair is listed under its owned member; the rank owning the ghost lists the mirror pair, so no forces need to be
/// sent back. Pairs closer than cutoff + skin at build time are listed (or than their species
/// pair's range + skin: set_pair_ranges); the list stays valid while no particle has moved more
/// than skin/2.
class NeighbourList {
public:
    NeighbourList() = default;
    NeighbourList(double cutoff, double skin) : cutoff_(cutoff), skin_(skin) {}

    double cutoff() const { return cutoff_; }
    double skin() const { return skin_; }
    double list_cutoff() const { return cutoff_ + skin_; }

    /// Ranges by species pair (ForceTerm::pair_ranges, the largest over the terms): `range`
    /// holds n x n entries, 0 where the pair never interacts. A pair is then listed only within
    /// its own range plus the skin; pairs with a species from n on within the cutoff's. An
    /// empty table: every pair within cutoff + skin.
    void set_pair_ranges(const std::vector<double>& range, int n_species);
    /// The list's ranges by species (n = n_range_species(); empty without ranges by species):
    /// n x n squared ranges by pair (row-major; -1 where never listed), then n ranges, the
    /// longest of each species (a search from it reaches no further).
    const std::vector<double>& range_table() const { return range_table_; }
    int n_range_species() const { return n_range_species_; }

    /// Builds from positions of owned particles and ghosts binned in `cells`.
    /// `owned_outside_domain`: owned particles may sit outside the domain (constituents of
    /// rigid bodies whose centre is inside) and ghosts inside it, so the search cannot rely on
    /// cells being purely owned or purely ghost. With rigid fields, spheres of the same body
    /// are never listed.
    void build(const ParticleStore& store, const CellList& cells, bool owned_outside_domain = false);

    /// Builds a full list instead: every owned i lists every j != i in range (ghosts
    /// included), so a per-particle loop can sum its own force without writing to partners —
    /// the layout of the GPU pair kernel (no atomics). Twice the entries of the half list.
    void build_full(const ParticleStore& store, const CellList& cells);

    /// Largest squared displacement of an owned particle since the last build; NaN if any
    /// position is not finite.
    double max_displacement_sq(const ParticleStore& store) const;

    /// True on every rank when some particle on any rank moved more than skin/2.
    bool needs_rebuild(const ParticleStore& store, MPI_Comm comm) const;
    /// The same from this rank's largest squared displacement, found elsewhere (on a back
    /// end). Collective; throws InstabilityError for a non-finite or impossible displacement.
    bool rebuild_due(double local_max_displacement_sq, MPI_Comm comm) const;
    /// The same from the largest squared displacement over all ranks (or a bound on it), reduced
    /// elsewhere (a NaN kept): not collective.
    bool rebuild_due(double global_max_displacement_sq) const;

    /// Owned positions when the list was built (the origin of the displacement check).
    const std::vector<Vec3>& reference_positions() const { return built_at_; }

    std::size_t n_owned() const { return offset_.empty() ? 0 : offset_.size() - 1; }
    std::size_t n_pairs() const { return n_pairs_; }
    const std::uint32_t* offsets() const { return offset_.data(); }
    const std::uint32_t* neighbours() const { return neighbour_.data(); }

private:
    void build_general(const ParticleStore& store, const CellList& cells, bool full);
    void build_general_half(const ParticleStore& store, const CellList& cells);
    void build_half_by_species(const ParticleStore& store, const CellList& cells);
    /// The squared ranges by species pair for the single-precision search (-1: never listed).
    std::vector<float> binned_pair_limits(const CellList& cells) const;
    /// How far a search from each species reaches (its longest range; the grid's when some
    /// particle's species has no row).
    std::vector<Int3> species_reach(const ParticleStore& store, const CellIndex& grid) const;
    void keep_reference(const ParticleStore& store, std::size_t n_owned);

    double cutoff_ = 0, skin_ = 0;
    std::vector<double> range_table_;
    int n_range_species_ = 0;
    std::size_t n_pairs_ = 0;
    std::vector<std::uint32_t> offset_, neighbour_;
    struct Place {
        std::uint32_t slot;  ///< index into the cells' members
        int cell;            ///< -1: not in an inner cell
    };
    std::vector<Place> place_;  ///< per owned particle, during build()
    std::vector<std::uint32_t> first_ghost_;  ///< per cell: the slot of its first ghost
    std::vector<int> slot_species_;           ///< per slot, during the general build
    std::vector<std::int64_t> slot_body_;     ///< per slot (by species: per sorted slot), during the build
    // The search by species (build_half_by_species): the cells' slots sorted by (species, cell),
    // the first of each (species, cell), and per sorted slot its position, particle and key.
    std::vector<std::uint32_t> by_species_first_, sorted_member_, sorted_key_;
    std::vector<BinnedPoint> sorted_x_;
    std::vector<Vec3> built_at_;
};

}  // namespace emergent

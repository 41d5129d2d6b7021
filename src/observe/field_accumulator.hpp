// SPDX-License-Identifier: MIT
// Coarse-grained density, flow velocity and temperature on a grid, averaged over an interval.
#pragma once

#include <mpi.h>

#include <vector>

#include "emergent/box.hpp"
#include "emergent/field_grid.hpp"
#include "emergent/particle_store.hpp"

namespace emergent {

/// Accumulates per-cell sums over samples; cost per sample is proportional to the particles
/// (one cell lookup each), and the cells are reduced across ranks only when a frame is taken.
class FieldAccumulator {
public:
    explicit FieldAccumulator(const FieldGrid& grid);

    const FieldGrid& grid() const { return grid_; }
    long long samples() const { return samples_; }

    /// Adds the owned particles of one instant (host code on a store). Positions are folded
    /// into `box` along its periodic axes first (between list builds particles may sit just
    /// outside it).
    void add(const ParticleStore& store, const std::vector<double>& species_mass, const Box& box);
    /// Adds one instant's per-cell sums (observe::kFieldSums per cell, e.g. from
    /// Simulation::field_sums, made where the particles live) and counts the sample.
    void add_sums(const std::vector<double>& sample);

    /// Reduces over ranks, returns the interval's averages (complete on rank 0) and restarts.
    /// Temperature uses the unbiased estimate with 3(n - 1) degrees of freedom per cell; cells
    /// with fewer than two samples get NaN temperature, and cells with none zero flow.
    FieldFrame take(MPI_Comm comm);

    /// The interval so far, summed over all ranks (for checkpoints). Collective.
    std::vector<double> global_sums(MPI_Comm comm) const;
    /// Continues an interval from global sums: rank 0 takes them, the others start empty.
    void restore(const std::vector<double>& sums, long long samples, int rank);

private:
    FieldGrid grid_;
    static constexpr int kSums = 6;  // per cell: count, mass, momentum (3), m v^2 (observe::kFieldSums)
    long long samples_ = 0;
    std::vector<double> sums_;
};

}  // namespace emergent

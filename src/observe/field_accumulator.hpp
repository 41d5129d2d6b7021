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

    /// Adds the owned particles of one instant. Positions are folded into `box` along its
    /// periodic axes first (between list builds particles may sit just outside it).
    void add(const ParticleStore& store, const std::vector<double>& species_mass, const Box& box);

    /// Adds one particle (position folded into the box, velocity, mass) to its cell, if any.
    void add_particle(const Vec3& x, const Vec3& velocity, double mass) {
        const int c = grid_.cell_of(x);
        if (c < 0) return;
        const Vec3 v = grid_.components(x, velocity);
        double* s = &sums_[static_cast<std::size_t>(c) * kSums];
        s[0] += 1;
        s[1] += mass;
        s[2] += mass * v.x;
        s[3] += mass * v.y;
        s[4] += mass * v.z;
        s[5] += mass * dot(v, v);
    }
    /// Closes one instant's sample (after its particles were added one by one).
    void count_sample() { ++samples_; }

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
    static constexpr int kSums = 6;  // per cell: count, mass, momentum (3), m v^2
    long long samples_ = 0;
    std::vector<double> sums_;
};

/// FieldAccumulator::add for several grids in one pass over the particles (each position is
/// folded into the box once, not once per grid).
void add_sample(std::vector<FieldAccumulator>& fields, const ParticleStore& store,
                const std::vector<double>& species_mass, const Box& box);

}  // namespace emergent

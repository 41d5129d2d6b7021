// SPDX-License-Identifier: MIT
// Coarse-graining accumulator.
#include "observe/field_accumulator.hpp"

#include "emergent/error.hpp"
#include "observe/field_sampling.hpp"

#include <cmath>
#include <stdexcept>

#include "emergent/execution.hpp"

namespace emergent {

FieldAccumulator::FieldAccumulator(const FieldGrid& grid)
    : grid_(grid), sums_(static_cast<std::size_t>(grid.n_cells()) * kSums, 0.0) {}

void FieldAccumulator::add(const ParticleStore& store, const std::vector<double>& species_mass,
                           const Box& box) {
    std::vector<double> sample(sums_.size());
    observe::scatter_field_sums(grid_, box, store.n_owned(), store.position.data(), store.velocity.data(),
                                store.species.data(), species_mass.data(), sample.data());
    add_sums(sample);
}

void FieldAccumulator::add_sums(const std::vector<double>& sample) {
    if (sample.size() != sums_.size())
        throw std::logic_error("FieldAccumulator::add_sums: a sample of another grid than " + grid_.name);
    // Per sample, then into the interval's sums: the same additions wherever the sample was made.
    for (std::size_t k = 0; k < sums_.size(); ++k) sums_[k] += sample[k];
    ++samples_;
}

std::vector<double> FieldAccumulator::global_sums(MPI_Comm comm) const {
    std::vector<double> total(sums_.size());
    exec::count_collective();
    MPI_Allreduce(sums_.data(), total.data(), static_cast<int>(sums_.size()), MPI_DOUBLE, MPI_SUM,
                  comm);
    return total;
}

void FieldAccumulator::restore(const std::vector<double>& sums, long long samples, int rank) {
    // Sums kept by a run with another grid (a damaged checkpoint, or fields.grid changed).
    if (sums.size() != sums_.size())
        throw InputError("field '" + grid_.name + "': the checkpoint's grid holds " + std::to_string(sums.size() / kSums) +
                         " cells, this run's " + std::to_string(sums_.size() / kSums) +
                         " (a continuation keeps the grids it was written with)");
    if (rank == 0) sums_ = sums;
    samples_ = samples;
}

FieldFrame FieldAccumulator::take(MPI_Comm comm) {
    exec::count_collective();
    MPI_Allreduce(MPI_IN_PLACE, sums_.data(), static_cast<int>(sums_.size()), MPI_DOUBLE, MPI_SUM,
                  comm);
    const int n = grid_.n_cells();
    FieldFrame f;
    f.density.resize(n);
    f.velocity.resize(3 * static_cast<std::size_t>(n));
    f.temperature.resize(n);
    f.count.resize(n);
    for (int c = 0; c < n; ++c) {
        const double* s = &sums_[static_cast<std::size_t>(c) * kSums];
        f.count[c] = s[0];
        f.density[c] = samples_ > 0 ? s[0] / (samples_ * grid_.cell_volume(c)) : 0.0;
        const double p2 = s[2] * s[2] + s[3] * s[3] + s[4] * s[4];
        for (int d = 0; d < 3; ++d) f.velocity[3 * c + d] = s[1] > 0 ? s[2 + d] / s[1] : 0.0;
        // sum m (v - u)^2 = sum m v^2 - |sum m v|^2 / sum m, over 3(n - 1) degrees of freedom.
        f.temperature[c] = s[0] > 1 ? (s[5] - p2 / s[1]) / (3 * (s[0] - 1)) : NAN;
    }
    std::fill(sums_.begin(), sums_.end(), 0.0);
    samples_ = 0;
    return f;
}

}  // namespace emergent

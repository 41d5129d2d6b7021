// SPDX-License-Identifier: MIT
// Coarse-graining accumulator.
#include "observe/field_accumulator.hpp"

#include <cmath>
#include <stdexcept>

namespace emergent {

FieldAccumulator::FieldAccumulator(const FieldGrid& grid)
    : grid_(grid), sums_(static_cast<std::size_t>(grid.n_cells()) * kSums, 0.0) {}

namespace {
template <class Each>
void for_each_owned(const ParticleStore& store, const std::vector<double>& species_mass,
                    const Box& box, Each&& each) {
    for (std::size_t i = 0; i < store.n_owned(); ++i) {
        // Between list builds owned particles may sit just past a periodic face; a hair below
        // lo must land at lo, not round up to hi (outside every cell).
        each(box.primary_image(store.position[i]), store.velocity[i],
             species_mass[store.species[i]]);
    }
}
}  // namespace

void FieldAccumulator::add(const ParticleStore& store, const std::vector<double>& species_mass,
                           const Box& box) {
    for_each_owned(store, species_mass, box,
                   [&](const Vec3& x, const Vec3& v, double m) { add_particle(x, v, m); });
    count_sample();
}

void add_sample(std::vector<FieldAccumulator>& fields, const ParticleStore& store,
                const std::vector<double>& species_mass, const Box& box) {
    for_each_owned(store, species_mass, box, [&](const Vec3& x, const Vec3& v, double m) {
        for (FieldAccumulator& f : fields) f.add_particle(x, v, m);
    });
    for (FieldAccumulator& f : fields) f.count_sample();
}

std::vector<double> FieldAccumulator::global_sums(MPI_Comm comm) const {
    std::vector<double> total(sums_.size());
    MPI_Allreduce(sums_.data(), total.data(), static_cast<int>(sums_.size()), MPI_DOUBLE, MPI_SUM,
                  comm);
    return total;
}

void FieldAccumulator::restore(const std::vector<double>& sums, long long samples, int rank) {
    if (sums.size() != sums_.size())
        throw std::logic_error("FieldAccumulator::restore: grid " + grid_.name + " changed");
    if (rank == 0) sums_ = sums;
    samples_ = samples;
}

FieldFrame FieldAccumulator::take(MPI_Comm comm) {
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

// SPDX-License-Identifier: MIT
// Thermostatting of the fluid layer next to a thermal wall.
#pragma once

#include <mpi.h>

#include <vector>

#include "emergent/backend_particles.hpp"
#include "emergent/particle_store.hpp"

namespace emergent {

/// The fluid layer between `lo` and `hi` along `axis` (e.g. within r_c of a wall), held at the
/// wall's temperature: every `interval` steps the particles in it have their mean flow along
/// the wall (the two other axes) removed and their velocities scaled so that the layer's
/// temperature is `temperature`. Following Rapaport's Rayleigh-Benard walls, this stops any
/// drift building up along the wall and makes the wall temperature hold where collisions alone
/// leave a temperature jump; the motion across the wall (convection reaching it) is kept.
class WallLayerThermostat {
public:
    WallLayerThermostat(int axis, double lo, double hi, double temperature, long long interval);

    /// Acts on the owned particles where the back end holds them, when step % interval == 0.
    /// Collective: every rank calls it at every step.
    void apply(const BackendParticles& particles, MPI_Comm comm, long long step);

    /// apply() in two halves, so that the engine sums several layers' measures in one
    /// collective: whether it acts at this step; this rank's part of the layer's kSums sums
    /// (mass, momentum, twice the kinetic energy, count); the rescaling from the sums over all
    /// ranks.
    static constexpr int kSums = 6;
    bool due(long long step) const { return step % interval_ == 0; }
    void measure(const BackendParticles& particles, double* sums) const;
    void rescale(const BackendParticles& particles, const double* all);
    /// Whether the two layers may share a particle (then one rescales after the other).
    bool overlaps(const WallLayerThermostat& other) const {
        return axis_ != other.axis_ || (lo_ < other.hi_ && other.lo_ < hi_);
    }

    /// Kinetic energy the layer rescaling has given the fluid since it was made (all ranks;
    /// the same on every rank). Negative where it cools.
    double energy() const { return energy_; }
    /// Sets the tally (a run continued from a checkpoint).
    void set_energy(double e) { energy_ = e; }

private:
    int axis_;
    double lo_, hi_, temperature_;
    long long interval_;
    double energy_ = 0;
};

}  // namespace emergent

// SPDX-License-Identifier: MIT
// The GPU path, seen from host code: which device a rank uses, and a periodic system of point
// particles with one pair interaction that lives on the device for its whole run. This header
// needs no CUDA headers; without the CUDA back end every entry point throws a clear error.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "emergent/thermostat.hpp"
#include "emergent/vec3.hpp"

namespace emergent::gpu {

/// True when the CUDA back end is built and at least one CUDA device answers.
bool device_present();

struct DeviceInfo {
    int index = -1;
    std::string name;
    int multiprocessors = 0;
    std::size_t memory_bytes = 0;
};

/// Chooses the device for this process: local rank (Open MPI, SLURM, MPICH variables) modulo
/// the device count. Throws "no CUDA device" when CUDA was requested but none is present.
DeviceInfo select_device();

/// Device memory in use on the current device, by every process (total minus free).
std::size_t device_memory_in_use();

/// Measured device-to-device copy rate in bytes per second (bytes read plus bytes written),
/// median of `repeats` copies of `bytes`: the bandwidth ceiling for roofline figures.
double copy_bandwidth(std::size_t bytes, int repeats);

/// Threads per particle for a loop over neighbours (or candidates): enough threads to fill the
/// device (2048 per multiprocessor), each with at least 3 to handle. Chosen from the sweep in
/// benchmarks/RESULTS.md (H100: 64000 LJ atoms best at 4-8, 1 million WCA atoms at 1).
int lanes_for(std::size_t particles, double mean_neighbours, int multiprocessors);

/// Arithmetic of the pair forces. Double is the reference; Mixed evaluates each pair in float
/// from a double separation and sums in double (positions, velocities and sums stay double).
enum class Precision { Double, Mixed };

/// Truncated, shifted Lennard-Jones fluid in an orthorhombic periodic box, integrated by
/// velocity Verlet (NVE) on one GPU.
struct PairSystemSpec {
    Vec3 box{0, 0, 0};
    double epsilon = 1, sigma = 1, cutoff = 1.122462048309373;
    double skin = 0.3;  ///< the list holds pairs within cutoff + skin
    double dt = 0.005;
    double mass = 1;
    Precision precision = Precision::Double;
    /// A run stops (InstabilityError) when a force exceeds this (0: no bound); the engine's
    /// guard.max_force default.
    double max_force = 1e5;
    int block_size = 256;  ///< threads per block of every per-particle kernel
    /// GPU threads sharing one particle's neighbour sum (1, 2, 4, ... 32); 0 chooses from the
    /// particle count and the mean neighbour count at each list build (see lanes_for()).
    int lanes_per_particle = 0;
};

/// Time-averaged-free instantaneous sums over all particles.
struct Thermo {
    double kinetic = 0;    ///< sum of m v^2 / 2
    double potential = 0;  ///< sum of shifted pair energies
    double virial = 0;     ///< sum over pairs of r . f
};

/// Device time per part of a step, from CUDA events (profiling runs only: the events add a
/// synchronisation per part).
struct StepProfile {
    /// ms, summed over the steps; `kick` is the second kick with the rebuild check fused in.
    double kick_drift = 0, rebuild = 0, force = 0, kick = 0;
    long steps = 0;
};

struct ListStats {
    long builds = 0;
    double mean_neighbours = 0;  ///< full list, at the last build
    std::uint32_t capacity = 0;  ///< neighbour slots per particle
    int lanes = 1;               ///< threads per particle of the force pass
};

class PeriodicPairSystem {
  public:
    /// Particles start at x (inside the box) with velocities v; particle i has id i.
    PeriodicPairSystem(const PairSystemSpec& spec, const std::vector<Vec3>& x, const std::vector<Vec3>& v);
    ~PeriodicPairSystem();
    PeriodicPairSystem(const PeriodicPairSystem&) = delete;
    PeriodicPairSystem& operator=(const PeriodicPairSystem&) = delete;

    /// Advances `steps` velocity-Verlet steps; returns when the device has finished them.
    /// Throws InstabilityError when a position, velocity or force becomes non-finite or a force
    /// exceeds spec.max_force (checked on the device every step, in the pass that decides the
    /// rebuilds).
    void run(long steps);
    /// Energies and virial of the current state (one extra force pass with sampling on).
    Thermo thermo();
    /// v *= factor for every particle (the engine's velocity-rescaling functor).
    void scale_velocities(double factor);
    /// Rescales velocities every `interval` steps by the thermostat's factor (the engine's
    /// Thermostat, e.g. make_bussi_thermostat; 3N - 3 degrees of freedom, its random stream
    /// keyed by the step index). Each application costs one reduction and a host round trip.
    void set_thermostat(std::unique_ptr<Thermostat> thermostat, int interval = 1);
    /// Unwrapped positions and velocities in id order.
    std::vector<Vec3> positions() const;
    std::vector<Vec3> velocities() const;

    std::size_t size() const;
    ListStats list_stats() const;
    /// Device memory held by this system (its buffers, the list and the sort's scratch).
    std::size_t device_bytes() const;
    void set_profiling(bool on);
    StepProfile profile() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace emergent::gpu

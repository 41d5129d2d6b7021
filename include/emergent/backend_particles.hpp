// SPDX-License-Identifier: MIT
// The particles as the back end's loops see them: pointers into the back end's memory (the
// store's own arrays on the host back end), with the full neighbour list where the force terms
// read it. What force terms, walls and thermostats written as functors receive.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "emergent/execution.hpp"
#include "emergent/particle_store.hpp"

namespace emergent {

/// Optional fields are null where absent. Force terms only read positions and velocities;
/// boundary rules and thermostats move them.
struct BackendParticles {
    Vec3* position = nullptr;
    Vec3* velocity = nullptr;
    Vec3* force = nullptr;
    const int* species = nullptr;
    const std::int64_t* id = nullptr;
    const Real* diameter = nullptr;
    const double* mass = nullptr;  ///< per species
    std::size_t n_owned = 0, size = 0;
    /// Full neighbour list: every owned particle lists each neighbour j != i in range, ghosts
    /// included, so a per-particle loop sums its own force and writes nothing else (the
    /// layout a device needs: no atomics). Neighbours of i: list_index[list_offset[i] ..
    /// list_offset[i + 1]). Null unless the run uses it (ListLayout).
    const std::uint32_t* list_offset = nullptr;
    const std::uint32_t* list_index = nullptr;
    /// Per-particle scratch of n_owned values each, for sampling steps: energy, virial, and the
    /// largest contact overlap (granular terms).
    Real* energy = nullptr;
    Real* virial = nullptr;
    Real* overlap = nullptr;
    /// Where loops over these arrays run: launch through it (exec::for_each(p.target, ...));
    /// the host reads single values with exec::read_one(p.target, ...), never directly.
    exec::Target target;
};

/// The store's own arrays (the host back end; tests). `mass` per species.
inline BackendParticles host_view(ParticleStore& s, const std::vector<double>& mass) {
    BackendParticles p;
    p.position = s.position.data();
    p.velocity = s.velocity.data();
    p.force = s.force.data();
    p.species = s.species.data();
    p.id = s.id.data();
    p.diameter = s.has_diameters() ? s.diameter.data() : nullptr;
    p.mass = mass.data();
    p.n_owned = s.n_owned();
    p.size = s.size();
    return p;
}

}  // namespace emergent

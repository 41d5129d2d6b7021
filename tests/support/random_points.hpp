// SPDX-License-Identifier: MIT
// Particles at random in a box, for neighbour-search and pair-loop tests.
#pragma once

#include <cstdint>

#include "emergent/particle_store.hpp"
#include "emergent/random.hpp"
#include "emergent/vec3.hpp"

namespace emergent::fixtures {

/// Adds n particles at rest (species 0, ids 0 .. n-1) uniformly in [0, size), drawn from seed.
inline void add_uniform_particles(ParticleStore& store, const Vec3& size, int n,
                                  std::uint64_t seed) {
    for (int i = 0; i < n; ++i)
        store.add_owned({size.x * uniform_open(seed, i, 0), size.y * uniform_open(seed, i, 1),
                         size.z * uniform_open(seed, i, 2)},
                        {0, 0, 0}, 0, i);
}

}  // namespace emergent::fixtures

// SPDX-License-Identifier: MIT
// Packs chosen per-particle fields of chosen particles into a byte buffer and back.
#pragma once

#include <cstddef>
#include <vector>

#include "emergent/particle_store.hpp"

namespace emergent::decomp {

/// Bytes one particle occupies when the fields in `mask` are packed.
std::size_t packed_bytes(ParticleStore& store, unsigned mask);

/// Appends the fields in `mask` of particles `index[0..n)` to `buffer`, particle by particle.
void pack_fields(ParticleStore& store, unsigned mask, const int* index, std::size_t n,
                 std::vector<char>& buffer);

/// Writes `n` packed particles from `buffer` into slots [first, first + n) of the store,
/// which must already be large enough.
void unpack_fields(ParticleStore& store, unsigned mask, const char* buffer, std::size_t n,
                   std::size_t first);

}  // namespace emergent::decomp

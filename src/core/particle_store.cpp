// SPDX-License-Identifier: MIT
// Structure-of-arrays particle storage.
#include "emergent/particle_store.hpp"

#include <algorithm>
#include <cstring>
#include <type_traits>

namespace emergent {

namespace {
/// Resizes with room for 1/32 more: ghost counts change by a fraction of a percent from build
/// to build, and the doubling of std::vector would leave up to half of each array unused (at
/// 256 000 atoms the appended ghosts took the store from 104 to 208 bytes per atom).
template <class T>
void grow(std::vector<T>& v, std::size_t n, const T& fill) {
    if (n > v.capacity()) v.reserve(n + n / 32);
    v.resize(n, fill);
}
}  // namespace

void ParticleStore::resize_all(std::size_t n) {
    for_each_array([&](const auto& entry, auto& array) { grow(array, n, entry.fill); });
}

void ParticleStore::fit_capacity() {
    for_each_array([](const auto&, auto& array) {
        std::decay_t<decltype(array)>(array.begin(), array.end()).swap(array);
    });
}

void ParticleStore::copy_owned(const ParticleStore& from, unsigned fields) {
    rigid_ = from.rigid_;
    diameters_ = from.diameters_;
    n_owned_ = from.n_owned_;
    for_each_array([&](const auto& entry, auto& mine) {
        const auto& theirs = from.*entry.member;
        if (fields & entry.mask)
            mine.assign(theirs.begin(), theirs.begin() + static_cast<std::ptrdiff_t>(n_owned_));
        else
            std::decay_t<decltype(mine)>().swap(mine);
    });
}

void ParticleStore::enable_diameters() {
    if (diameters_) return;
    diameters_ = true;
    diameter.assign(position.size(), 1);
}

void ParticleStore::enable_rigid_fields() {
    rigid_ = true;
    resize_all(position.size());
}

void ParticleStore::add_owned(const Vec3& x, const Vec3& v, int species_index,
                              std::int64_t global_id, Real particle_diameter) {
    resize_all(n_owned_);  // drops any ghosts, so the new element starts from the fill values
    resize_all(n_owned_ + 1);
    position[n_owned_] = x;
    velocity[n_owned_] = v;
    species[n_owned_] = species_index;
    id[n_owned_] = global_id;
    if (particle_diameter != 1 && !diameters_) {
        enable_diameters();
        diameter.resize(n_owned_ + 1, 1);
    }
    if (diameters_) diameter[n_owned_] = particle_diameter;
    ++n_owned_;
}

void ParticleStore::resize_owned(std::size_t n) {
    n_owned_ = n;
    resize_all(n);
}

void ParticleStore::resize_ghosts(std::size_t n) { resize_all(n_owned_ + n); }

void ParticleStore::permute_owned(const std::vector<std::uint32_t>& order) {
    // In place: a copy of each field would add its whole size to the peak memory.
    const std::size_t n = order.size();
    const bool increasing = std::is_sorted(order.begin(), order.end());
    std::vector<bool> done(n == n_owned_ && !increasing ? n : 0);
    for_each_field([&](const FieldSpan& f) {
        const std::size_t b = f.element_bytes;
        auto* a = static_cast<unsigned char*>(f.data);
        if (increasing) {
            // A selection kept in order (order[k] >= k): each element moves down, never onto
            // one not yet read.
            for (std::size_t k = 0; k < n; ++k)
                if (order[k] != k) std::memcpy(a + k * b, a + order[k] * b, b);
            return;
        }
        if (n != n_owned_) {
            // A selection in another order (not used by the engine): through a copy.
            std::vector<unsigned char> copy(n * b);
            for (std::size_t k = 0; k < n; ++k) std::memcpy(&copy[k * b], a + order[k] * b, b);
            std::memcpy(a, copy.data(), n * b);
            return;
        }
        // A permutation of all owned particles, cycle by cycle.
        unsigned char held[64];  // the largest field element (a quaternion) is 32 bytes
        done.assign(n, false);
        for (std::size_t start = 0; start < n; ++start) {
            if (done[start]) continue;
            std::memcpy(held, a + start * b, b);
            std::size_t k = start;
            for (std::size_t from = order[k]; from != start; k = from, from = order[k]) {
                std::memcpy(a + k * b, a + from * b, b);
                done[k] = true;
            }
            std::memcpy(a + k * b, held, b);
            done[k] = true;
        }
    });
}

}  // namespace emergent

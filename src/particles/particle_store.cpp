// SPDX-License-Identifier: MIT
// Structure-of-arrays particle storage.
#include "emergent/particle_store.hpp"

#include <stdexcept>

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

void ParticleStore::reserve(std::size_t n) {
    for_each_array([&](const auto&, auto& array) { array.reserve(n); });
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
    if (deferred_) throw std::logic_error("ParticleStore::add_owned during a deferred resize");
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
    if (deferred_)
        deferred_size_ = n;
    else
        resize_all(n);
}

void ParticleStore::resize_ghosts(std::size_t n) {
    if (deferred_)
        deferred_size_ = n_owned_ + n;
    else
        resize_all(n_owned_ + n);
}

void ParticleStore::begin_deferred_resize() {
    if (deferred_) return;
    deferred_size_ = position.size();
    deferred_ = true;
}

void ParticleStore::end_deferred_resize() {
    if (!deferred_) return;
    deferred_ = false;
    resize_all(deferred_size_);
}

void ParticleStore::permute_owned(const std::vector<std::uint32_t>& order, unsigned fields) {
    const std::size_t n = order.size();
    if (std::is_sorted(order.begin(), order.end())) {
        // A selection kept in order (order[k] >= k): each element moves down, never onto one
        // not yet read, so no copy is needed.
        for_each_field([&](const FieldSpan& f) {
            if (!(fields & f.field)) return;
            const std::size_t b = f.element_bytes;
            auto* a = static_cast<unsigned char*>(f.data);
            for (std::size_t k = 0; k < n; ++k)
                if (order[k] != k) std::memcpy(a + k * b, a + order[k] * b, b);
        });
        return;
    }
    // Gathered word by word (8 bytes: a Vec3 is moved as three doubles) through one buffer of
    // that size, allocated for this call only: a buffer of whole elements would add 24 bytes a
    // particle to the peak, following the permutation's cycles in place was 7 % slower (two
    // random accesses per element).
    std::vector<std::uint64_t> word(n);
    for_each_field([&](const FieldSpan& f) {
        if (!(fields & f.field)) return;
        auto* a = static_cast<unsigned char*>(f.data);
        const std::size_t b = f.element_bytes;
        for (std::size_t at = 0; at < b; at += sizeof(std::uint64_t)) {
            const std::size_t w = std::min(sizeof(std::uint64_t), b - at);
            for (std::size_t k = 0; k < n; ++k) std::memcpy(&word[k], a + order[k] * b + at, w);
            for (std::size_t k = 0; k < n; ++k) std::memcpy(a + k * b + at, &word[k], w);
        }
    });
}

}  // namespace emergent

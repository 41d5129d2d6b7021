// SPDX-License-Identifier: MIT
// Structure-of-arrays particle storage.
#include "emergent/particle_store.hpp"

#include <cstring>

namespace emergent {

void ParticleStore::resize_all(std::size_t n) {
    position.resize(n);
    velocity.resize(n);
    force.resize(n);
    species.resize(n);
    id.resize(n);
    image.resize(n);
    diameter.resize(n);
    if (rigid_) {
        body.resize(n, -1);
        orientation.resize(n);
        angular_momentum.resize(n, Quat{0, 0, 0, 0});
        torque.resize(n, Vec3{0, 0, 0});
    }
}

void ParticleStore::enable_rigid_fields() {
    rigid_ = true;
    resize_all(position.size());
}

void ParticleStore::add_owned(const Vec3& x, const Vec3& v, int species_index,
                              std::int64_t global_id, Real particle_diameter) {
    resize_all(n_owned_);
    position.push_back(x);
    velocity.push_back(v);
    force.push_back({0, 0, 0});
    species.push_back(species_index);
    id.push_back(global_id);
    image.push_back({0, 0, 0});
    diameter.push_back(particle_diameter);
    if (rigid_) {
        body.push_back(-1);
        orientation.push_back(Quat{});
        angular_momentum.push_back(Quat{0, 0, 0, 0});
        torque.push_back({0, 0, 0});
    }
    ++n_owned_;
}

void ParticleStore::resize_owned(std::size_t n) {
    n_owned_ = n;
    resize_all(n);
}

void ParticleStore::resize_ghosts(std::size_t n) { resize_all(n_owned_ + n); }

void ParticleStore::permute_owned(const std::vector<std::uint32_t>& order) {
    const std::size_t n = order.size();
    for_each_field([&](const FieldSpan& f) {
        const std::size_t b = f.element_bytes;
        scratch_.resize(n * b);
        auto* src = static_cast<unsigned char*>(f.data);
        for (std::size_t k = 0; k < n; ++k) std::memcpy(&scratch_[k * b], src + order[k] * b, b);
        std::memcpy(src, scratch_.data(), n * b);
    });
}

}  // namespace emergent

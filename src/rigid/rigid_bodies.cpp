// SPDX-License-Identifier: MIT
// Rigid bodies: bookkeeping and integration.
#include "rigid/rigid_bodies.hpp"

#include <stdexcept>

#include "emergent/error.hpp"
#include "rigid/no_squish.hpp"

namespace emergent::rigid {

int RigidBodies::add_kind(const BodyKind& kind, const std::vector<double>& species_mass) {
    BodyShape shape;
    shape.positions = kind.positions;
    shape.diameters = kind.diameters;
    for (int s : kind.species) {
        if (s < 0 || s >= static_cast<int>(species_mass.size()))
            throw InputError("rigid body: constituent species " + std::to_string(s) + " has no mass");
        shape.masses.push_back(species_mass[s]);
    }
    if (kind.positions.empty() || kind.species.size() != kind.positions.size() ||
        kind.diameters.size() != kind.positions.size())
        throw InputError("rigid body: each constituent needs a position, species and diameter");
    frames_.push_back(principal_frame(shape));
    kinds_.push_back(kind);
    kind_masses_.push_back(shape.masses);
    max_extent_ = std::max(max_extent_, frames_.back().extent);
    if (!bodies_.has_rigid_fields()) bodies_.enable_rigid_fields();
    return static_cast<int>(kinds_.size()) - 1;
}

void RigidBodies::add(int kind, const Vec3& com, const Quat& orientation, const Vec3& velocity,
                      const Vec3& omega, std::int64_t id, std::int64_t first_particle_id) {
    const BodyFrame& f = frames_.at(kind);
    const std::size_t b = bodies_.n_owned();
    bodies_.add_owned(com, velocity, kind, id);
    // The kind's principal frame, then the requested orientation.
    bodies_.orientation[b] = normalized(orientation * f.orientation);
    bodies_.body[b] = first_particle_id;
    Rotor r{bodies_.orientation[b], Quat{0, 0, 0, 0}, f.inertia};
    set_angular_velocity(r, rotate_back(r.q, omega));
    bodies_.angular_momentum[b] = r.p;
}

Vec3 RigidBodies::omega_space(std::size_t b) const {
    const Rotor r{bodies_.orientation[b], bodies_.angular_momentum[b],
                  frames_[bodies_.species[b]].inertia};
    return rotate(r.q, angular_velocity_body(r));
}

void RigidBodies::drop_constituents(ParticleStore& store) const {
    std::vector<std::uint32_t> keep;
    for (std::size_t i = 0; i < store.n_owned(); ++i)
        if (store.body[i] < 0) keep.push_back(static_cast<std::uint32_t>(i));
    store.permute_owned(keep);
    store.resize_owned(keep.size());
}

void RigidBodies::place(ParticleStore& store, std::size_t b, bool velocities_only) const {
    const BodyFrame& f = frames_[bodies_.species[b]];
    const Vec3 R = bodies_.position[b], V = bodies_.velocity[b], w = omega_space(b);
    for (std::size_t k = 0; k < f.positions.size(); ++k) {
        const std::uint32_t i = index_[first_[b] + k];
        const Vec3 arm = rotate(bodies_.orientation[b], f.positions[k]);
        if (!velocities_only) store.position[i] = R + arm;
        store.velocity[i] = V + cross(w, arm);
    }
}

void RigidBodies::append_constituents(ParticleStore& store) const {
    for (std::size_t b = 0; b < bodies_.n_owned(); ++b) {
        const int kind = bodies_.species[b];
        const BodyFrame& f = frames_[kind];
        const Vec3 R = bodies_.position[b], V = bodies_.velocity[b], w = omega_space(b);
        for (std::size_t k = 0; k < f.positions.size(); ++k) {
            const Vec3 arm = rotate(bodies_.orientation[b], f.positions[k]);
            store.add_owned(R + arm, V + cross(w, arm), kinds_[kind].species[k],
                            bodies_.body[b] + static_cast<std::int64_t>(k), kinds_[kind].diameters[k]);
            store.body.back() = bodies_.id[b];
            store.image.back() = bodies_.image[b];
        }
    }
}

void RigidBodies::index_constituents(const ParticleStore& store) {
    std::unordered_map<std::int64_t, std::uint32_t> local;
    first_.assign(bodies_.n_owned() + 1, 0);
    for (std::size_t b = 0; b < bodies_.n_owned(); ++b) {
        local[bodies_.id[b]] = static_cast<std::uint32_t>(b);
        first_[b + 1] = first_[b] + static_cast<std::uint32_t>(frames_[bodies_.species[b]].positions.size());
    }
    index_.assign(first_.back(), ~0u);
    for (std::size_t i = 0; i < store.n_owned(); ++i) {
        if (store.body[i] < 0) continue;
        const std::uint32_t b = local.at(store.body[i]);
        index_[first_[b] + (store.id[i] - bodies_.body[b])] = static_cast<std::uint32_t>(i);
    }
}

void RigidBodies::kick_drift(ParticleStore& store, double kick, double drift) {
    for (std::size_t b = 0; b < bodies_.n_owned(); ++b) {
        const BodyFrame& f = frames_[bodies_.species[b]];
        bodies_.velocity[b] += (kick / f.mass) * bodies_.force[b];
        bodies_.position[b] += drift * bodies_.velocity[b];
        Rotor r{bodies_.orientation[b], bodies_.angular_momentum[b], f.inertia};
        torque_kick(r, bodies_.torque[b], kick);
        rotate_freely(r, drift);
        bodies_.orientation[b] = r.q;
        bodies_.angular_momentum[b] = r.p;
        place(store, b, false);
    }
}

void RigidBodies::sum_forces(const ParticleStore& store) {
    for (std::size_t b = 0; b < bodies_.n_owned(); ++b) {
        Vec3 F{0, 0, 0}, T{0, 0, 0};
        for (std::uint32_t k = first_[b]; k < first_[b + 1]; ++k) {
            const std::uint32_t i = index_[k];
            F += store.force[i];
            T += cross(store.position[i] - bodies_.position[b], store.force[i]);
        }
        bodies_.force[b] = F;
        bodies_.torque[b] = T;
    }
}

void RigidBodies::kick(ParticleStore& store, double kick) {
    for (std::size_t b = 0; b < bodies_.n_owned(); ++b) {
        const BodyFrame& f = frames_[bodies_.species[b]];
        bodies_.velocity[b] += (kick / f.mass) * bodies_.force[b];
        Rotor r{bodies_.orientation[b], bodies_.angular_momentum[b], f.inertia};
        torque_kick(r, bodies_.torque[b], kick);
        bodies_.angular_momentum[b] = r.p;
        place(store, b, true);
    }
}

double RigidBodies::kinetic() const {
    double k = 0;
    for (std::size_t b = 0; b < bodies_.n_owned(); ++b) {
        const BodyFrame& f = frames_[bodies_.species[b]];
        const Rotor r{bodies_.orientation[b], bodies_.angular_momentum[b], f.inertia};
        k += 0.5 * f.mass * dot(bodies_.velocity[b], bodies_.velocity[b]) + rotational_energy(r);
    }
    return k;
}

Vec3 RigidBodies::momentum() const {
    Vec3 p{0, 0, 0};
    for (std::size_t b = 0; b < bodies_.n_owned(); ++b)
        p += frames_[bodies_.species[b]].mass * bodies_.velocity[b];
    return p;
}

Vec3 RigidBodies::angular_momentum(const Vec3& box_length) const {
    Vec3 l{0, 0, 0};
    for (std::size_t b = 0; b < bodies_.n_owned(); ++b) {
        const BodyFrame& f = frames_[bodies_.species[b]];
        const Int3 n = bodies_.image[b];
        const Vec3 R = bodies_.position[b] + Vec3{n.x * box_length.x, n.y * box_length.y, n.z * box_length.z};
        const Rotor r{bodies_.orientation[b], bodies_.angular_momentum[b], f.inertia};
        l += f.mass * cross(R, bodies_.velocity[b]) + rotate(r.q, body_angular_momentum(r));
    }
    return l;
}

}  // namespace emergent::rigid

// SPDX-License-Identifier: MIT
// Rigid bodies: bookkeeping and integration.
#include "rigid/rigid_bodies.hpp"

#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "emergent/error.hpp"
#include "emergent/execution.hpp"
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
    double mass = 0;
    for (double m : shape.masses) mass += m;
    if (!(mass > 0)) throw InputError("rigid body: its constituents' masses sum to 0");
    frames_.push_back(principal_frame(shape));
    const BodyFrame& f = frames_.back();
    frame_mass_.push_back(f.mass);
    frame_inertia_.push_back(f.inertia);
    frame_positions_.insert(frame_positions_.end(), f.positions.begin(), f.positions.end());
    frame_species_.insert(frame_species_.end(), kind.species.begin(), kind.species.end());
    frame_diameters_.insert(frame_diameters_.end(), kind.diameters.begin(), kind.diameters.end());
    frame_first_.push_back(static_cast<std::uint32_t>(frame_positions_.size()));
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

void RigidBodies::drop_constituents(ParticleStore& store) const {
    std::vector<std::uint32_t> keep;
    for (std::size_t i = 0; i < store.n_owned(); ++i)
        if (store.body[i] < 0) keep.push_back(static_cast<std::uint32_t>(i));
    store.permute_owned(keep);
    store.resize_owned(keep.size());
}

RigidBodies::Arrays RigidBodies::host_arrays() const {
    auto& b = const_cast<ParticleStore&>(bodies_);
    return {{b.position.data(), b.velocity.data(), b.force.data(), b.orientation.data(),
             b.angular_momentum.data(), b.torque.data(), b.species.data()},
            {frame_mass_.data(), frame_inertia_.data(), frame_first_.data(), frame_positions_.data()},
            {first_.data(), index_.data()},
            b.id.data(),
            b.image.data()};
}

void RigidBodies::append_constituents(ParticleStore& store) const {
    std::vector<std::uint32_t> first(bodies_.n_owned() + 1, 0), slots;
    for (std::size_t b = 0; b < bodies_.n_owned(); ++b) {
        const int kind = bodies_.species[b];
        const std::size_t n = frames_[kind].positions.size();
        first[b + 1] = first[b] + static_cast<std::uint32_t>(n);
        for (std::size_t k = 0; k < n; ++k) {
            slots.push_back(static_cast<std::uint32_t>(store.n_owned()));
            store.add_owned(Vec3{0, 0, 0}, Vec3{0, 0, 0}, kinds_[kind].species[k],
                            bodies_.body[b] + static_cast<std::int64_t>(k), kinds_[kind].diameters[k]);
            store.body.back() = bodies_.id[b];
            store.image.back() = bodies_.image[b];
        }
    }
    // Positions and velocities by the step's own placement (place_constituents), the code the
    // back end's list build runs too: the same bits wherever a build runs.
    place_at(exec::Target{}, host_arrays(), ConstituentIndex{first.data(), slots.data()}, store.position.data(),
             store.velocity.data());
}

namespace {
struct PlaceAt {
    BodyState s;
    FrameTable frames;
    ConstituentIndex at;
    Vec3* x;
    Vec3* v;
    EMERGENT_HD void operator()(std::size_t b) const { place_constituents(s, frames, at, b, x, v, false); }
};
}  // namespace

void RigidBodies::place_at(const exec::Target& target, const Arrays& a, const ConstituentIndex& at, Vec3* x,
                           Vec3* v) const {
    exec::for_each(target, bodies_.n_owned(), PlaceAt{a.state, a.frames, at, x, v});
}

namespace {
/// Owned bodies by id, and where each one's constituents lie in a list of all of them (body b's
/// from first[b] to first[b + 1]); bad_kind is the first body whose kind has no frame (or none:
/// the count of bodies, and the layout stops there).
struct ConstituentLayout {
    std::unordered_map<std::int64_t, std::uint32_t> local;
    std::vector<std::uint32_t> first{0};
    std::size_t bad_kind = 0;
};

ConstituentLayout constituent_layout(const ParticleStore& bodies, const std::vector<BodyFrame>& frames) {
    ConstituentLayout l;
    for (l.bad_kind = 0; l.bad_kind < bodies.n_owned(); ++l.bad_kind) {
        const int kind = bodies.species[l.bad_kind];
        if (kind < 0 || static_cast<std::size_t>(kind) >= frames.size()) break;
        l.local[bodies.id[l.bad_kind]] = static_cast<std::uint32_t>(l.bad_kind);
        l.first.push_back(l.first.back() + static_cast<std::uint32_t>(frames[kind].positions.size()));
    }
    return l;
}
}  // namespace

void RigidBodies::index_constituents(const ParticleStore& store) {
    ConstituentLayout layout = constituent_layout(bodies_, frames_);
    first_ = std::move(layout.first);
    index_.assign(first_.back(), ~0u);
    for (std::size_t i = 0; i < store.n_owned(); ++i) {
        if (store.body[i] < 0) continue;
        const std::uint32_t b = layout.local.at(store.body[i]);
        index_[first_[b] + (store.id[i] - bodies_.body[b])] = static_cast<std::uint32_t>(i);
    }
}

std::string RigidBodies::check_constituents(const ParticleStore& store) const {
    const ConstituentLayout layout = constituent_layout(bodies_, frames_);
    if (layout.bad_kind < bodies_.n_owned())
        return "body " + std::to_string(bodies_.id[layout.bad_kind]) + " has kind " +
               std::to_string(bodies_.species[layout.bad_kind]) + ", which the scene does not declare";
    const std::vector<std::uint32_t>& first = layout.first;
    auto stray = [](std::int64_t particle, std::int64_t body) {
        return "particle " + std::to_string(particle) + " of body " + std::to_string(body) +
               " is not on its body's rank";
    };
    std::vector<char> seen(first.back(), 0);
    for (std::size_t i = 0; i < store.n_owned(); ++i) {
        if (store.body[i] < 0) continue;
        const auto it = layout.local.find(store.body[i]);
        if (it == layout.local.end()) return stray(store.id[i], store.body[i]);
        const std::size_t b = it->second;
        const std::int64_t offset = store.id[i] - bodies_.body[b];
        if (offset < 0 || static_cast<std::size_t>(offset) >= first[b + 1] - first[b])
            return "particle " + std::to_string(store.id[i]) + " is not one of body " +
                   std::to_string(bodies_.id[b]) + "'s spheres (they start at particle " +
                   std::to_string(bodies_.body[b]) + ")";
        seen[first[b] + static_cast<std::size_t>(offset)] = 1;
    }
    // A sphere missing here is on another rank (which names it too) or nowhere.
    for (std::size_t b = 0; b < bodies_.n_owned(); ++b)
        for (std::size_t j = first[b]; j < first[b + 1]; ++j)
            if (!seen[j]) return stray(bodies_.body[b] + static_cast<std::int64_t>(j - first[b]), bodies_.id[b]);
    return {};
}

void RigidBodies::kick_drift(const exec::Target& target, const Arrays& a, Vec3* x, Vec3* v, double kick,
                             double drift) const {
    exec::for_each(target, bodies_.n_owned(),
                   BodyKickDrift{a.state, a.frames, a.constituents, x, v, kick, drift});
}

void RigidBodies::sum_forces(const exec::Target& target, const Arrays& a, const Vec3* x, const Vec3* f) const {
    exec::for_each(target, bodies_.n_owned(), BodyForceAndTorque{a.state, a.constituents, x, f});
}

void RigidBodies::kick(const exec::Target& target, const Arrays& a, Vec3* x, Vec3* v, double kick,
                       bool place) const {
    exec::for_each(target, bodies_.n_owned(), BodyKick{a.state, a.frames, a.constituents, x, v, kick, place});
}

void RigidBodies::langevin(const exec::Target& target, const Arrays& a, Vec3* x, Vec3* v, double decay_t,
                           double decay_r, double temperature, std::uint64_t seed, std::uint64_t step) const {
    exec::for_each(target, bodies_.n_owned(),
                   BodyLangevin{a.state, a.frames, a.constituents, a.id, x, v, decay_t, decay_r,
                                temperature, seed, step});
}

double RigidBodies::kinetic(const exec::Target& target, const Arrays& a) const {
    return exec::transform_sum<double>(target, bodies_.n_owned(), BodyKinetic{{a.state, a.frames}});
}

Vec3 RigidBodies::kinetic_parts(const exec::Target& target, const Arrays& a) const {
    return exec::transform_sum<Vec3>(target, bodies_.n_owned(), BodyKineticParts{a.state, a.frames});
}

Vec3 RigidBodies::momentum(const exec::Target& target, const Arrays& a) const {
    return exec::transform_sum<Vec3>(target, bodies_.n_owned(), BodyMomentum{a.state, a.frames});
}

Vec3 RigidBodies::angular_momentum(const exec::Target& target, const Arrays& a, const Vec3& box_length) const {
    return exec::transform_sum<Vec3>(target, bodies_.n_owned(),
                                     BodyAngularMomentum{a.state, a.frames, a.image, box_length});
}

}  // namespace emergent::rigid

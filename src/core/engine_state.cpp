// SPDX-License-Identifier: MIT
#include "core/engine_state.hpp"

#include <type_traits>

#include "decomposition/reductions.hpp"
#include "emergent/error.hpp"
#include "emergent/execution.hpp"

namespace emergent {

rigid::RigidBodies::Arrays EngineState::body_arrays(unsigned fields) const {
    exec::ParticleMirror* m = bodies_resident.mirror();
    if (!m) return rigid.host_arrays();
    bodies_resident.backend_reads(fields);
    rigid::RigidBodies::Arrays a;
    a.state = {m->array<Vec3>(kPosition), m->array<Vec3>(kVelocity), m->array<Vec3>(kForce),
               m->array<Quat>(kOrientation), m->array<Quat>(kAngularMomentum), m->array<Vec3>(kTorque),
               m->array<int>(kSpecies)};
    a.frames = frames_on_backend;
    a.frames.mass = m->table(0, rigid.frame_masses());
    a.constituents = constituents_on_backend;
    a.id = m->array<std::int64_t>(kId);
    a.image = m->array<Int3>(kImage);
    return a;
}

void EngineState::place_body_frames() {
    exec::ParticleMirror* m = bodies_resident.mirror();
    if (!m || !bodies()) return;
    auto up = [&](std::size_t slot, const auto& v) {
        using T = typename std::decay_t<decltype(v)>::value_type;
        return static_cast<const T*>(m->upload(slot, v.data(), v.size() * sizeof(T)));
    };
    frames_on_backend.inertia = up(kFrameInertia, rigid.frame_inertia());
    frames_on_backend.first = up(kFrameFirst, rigid.frame_first());
    frames_on_backend.positions = up(kFramePositions, rigid.frame_positions());
    frame_species_on_backend = up(kFrameSpecies, rigid.frame_species());
    frame_diameters_on_backend = up(kFrameDiameters, rigid.frame_diameters());
}

void EngineState::place_constituents() {
    exec::ParticleMirror* m = bodies_resident.mirror();
    if (!m || !bodies()) return;
    const auto& first = rigid.constituent_first();
    const auto& index = rigid.constituent_index();
    constituents_on_backend.first = static_cast<const std::uint32_t*>(
        m->upload(kConstituentFirst, first.data(), first.size() * sizeof(std::uint32_t)));
    constituents_on_backend.index = static_cast<const std::uint32_t*>(
        m->upload(kConstituentIndex, index.data(), index.size() * sizeof(std::uint32_t)));
}

integrate::FreeKineticEnergy EngineState::kinetic_energy() const {
    particles.backend_reads(kVelocity | kSpecies | kBody);
    return {data(kVelocity, store.velocity), data(kSpecies, store.species), masses(),
            store.has_rigid_fields() ? data(kBody, store.body) : nullptr};
}

double EngineState::local_kinetic() const {
    const double sum = exec::transform_sum<double>(target, store.n_owned(), kinetic_energy());
    return sum + (bodies() ? rigid.kinetic(target, body_arrays(kVelocity | kSpecies | kOrientation |
                                                                kAngularMomentum))
                           : 0.0);
}

double EngineState::dof() const {
    const bool periodic = box.periodic[0] && box.periodic[1] && box.periodic[2];
    // In a fully periodic box total momentum is conserved: 3 fewer degrees of freedom.
    const double all = bodies() ? 3.0 * n_free + 6.0 * n_bodies : 3.0 * n_global;
    return all - (periodic ? 3.0 : 0.0);
}

void EngineState::count_bodies() {
    long long free_here = 0;
    particles.host_reads(kBody);
    for (std::size_t i = 0; i < store.n_owned(); ++i) free_here += is_free(i);
    n_free = decomp::sum(comm, free_here);
    n_bodies = decomp::sum(comm, static_cast<long long>(rigid.n_owned()));
}

void EngineState::agree_on_boundary_faults() {
    const std::string message = decomp::first_message(comm, boundary_fault);
    boundary_fault.clear();
    if (!message.empty()) throw InstabilityError(message);
}

}  // namespace emergent

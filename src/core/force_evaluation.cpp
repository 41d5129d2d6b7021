// SPDX-License-Identifier: MIT
#include "core/force_evaluation.hpp"

#include <algorithm>

#include "emergent/execution.hpp"
#include "integrate/kick_drift.hpp"

namespace emergent {

void ForceEvaluation::add(std::unique_ptr<ForceTerm> term) {
    s_.ghost_fields |= term->ghost_fields();
    s_.particle_fields |= term->particle_fields();
    terms_.push_back(std::move(term));
}

double ForceEvaluation::cutoff() const {
    double cutoff = 0;
    for (const auto& term : terms_) cutoff = std::max(cutoff, term->cutoff());
    return cutoff;
}

bool ForceEvaluation::conservative() const {
    return std::all_of(terms_.begin(), terms_.end(), [](const auto& term) { return term->conservative(); });
}

BackendParticles ForceEvaluation::backend_particles() {
    const ParticleStore& store = s_.store;
    BackendParticles p;
    p.position = s_.data(kPosition, store.position);
    p.velocity = s_.data(kVelocity, store.velocity);
    p.force = s_.data(kForce, store.force);
    p.species = s_.data(kSpecies, store.species);
    p.id = s_.data(kId, store.id);
    p.target = s_.target;
    p.diameter = store.has_diameters() ? s_.data(kDiameter, store.diameter) : nullptr;
    p.mass = s_.masses();
    p.n_owned = store.n_owned();
    p.size = store.size();
    p.list_offset = near_.list_offset();
    p.list_index = near_.list_index();
    const std::size_t bytes = p.n_owned * sizeof(Real);
    if (exec::ParticleMirror* mirror = s_.mirror()) {
        p.energy = static_cast<Real*>(mirror->scratch(EngineState::kEnergy, bytes));
        p.virial = static_cast<Real*>(mirror->scratch(EngineState::kVirial, bytes));
        p.overlap = static_cast<Real*>(mirror->scratch(EngineState::kOverlap, bytes));
    } else {
        energy_scratch_.resize(p.n_owned);
        virial_scratch_.resize(p.n_owned);
        overlap_scratch_.resize(p.n_owned);
        p.energy = energy_scratch_.data();
        p.virial = virial_scratch_.data();
        p.overlap = overlap_scratch_.data();
    }
    return p;
}

void ForceEvaluation::compute(bool sample, double at) {
    PhaseTimer timer(s_.times.force);
    if (near_.full_list())
        compute_on_backend(sample, at);
    else
        compute_on_host(sample, at);
}

void ForceEvaluation::compute_on_backend(bool sample, double at) {
    s_.particles.backend_reads(s_.particle_fields | s_.ghost_fields | kSpecies);
    BackendParticles particles = backend_particles();
    sums_ = ForceSums{};
    ForceContext context{&s_.mass, s_.box, at};
    // A first term that writes every owned force spares the pass clearing them. The ghosts'
    // are cleared once per build: no loop of the full list writes a ghost's force (they are
    // kept defined for whatever copies the whole array).
    const bool replace = !s_.bodies() && !terms_.empty() && terms_.front()->stores_on_backend();
    if (!replace) {
        exec::for_each(s_.target, particles.size, integrate::ZeroVector{particles.force});
    } else if (ghosts_cleared_at_ != near_.build_serial()) {
        exec::for_each(s_.target, particles.size - particles.n_owned,
                       integrate::ZeroVector{particles.force + particles.n_owned});
        ghosts_cleared_at_ = near_.build_serial();
    }
    for (const auto& term : terms_) {
        context.replace_forces = replace && term == terms_.front();
        term->add_forces_on_backend(particles, context, sample, sums_);
    }
    s_.particles.backend_wrote(kForce);
    if (s_.bodies()) {
        s_.rigid.sum_forces(s_.target, s_.body_arrays(kPosition), s_.data(kPosition, s_.store.position),
                            s_.data(kForce, s_.store.force));
        s_.bodies_resident.backend_wrote(kForce | kTorque);
    }
}

/// Force terms in their host form: host code on the store.
void ForceEvaluation::compute_on_host(bool sample, double at) {
    ParticleStore& store = s_.store;
    s_.particles.host_reads(s_.particle_fields | s_.ghost_fields | (s_.bodies() ? kPosition | kBody : 0u));
    std::fill(store.force.begin(), store.force.end(), Vec3{0, 0, 0});
    sums_ = ForceSums{};
    const ForceContext context{&s_.mass, s_.box, at};
    if (near_.refresh_in_flight())
        compute_overlapping_refresh(context, sample);
    else
        for (const auto& term : terms_) term->add_forces(store, near_.list(), context, sample, sums_);
    s_.particles.host_wrote(kForce);
    if (s_.bodies()) {
        // Host code summed the forces: the bodies' sums run on the host too.
        s_.bodies_resident.host_reads(kPosition);
        s_.rigid.sum_forces(exec::Target{}, s_.rigid.host_arrays(), store.position.data(), store.force.data());
        s_.bodies_resident.host_wrote(kForce | kTorque);
    }
}

// The first term's interior rows, a share of them per stage of the refresh; then its other rows
// and every other term, in the order of the plain loop, so each force sums the same terms in the
// same order. Each stage's share goes in kPokes pieces with a call into MPI between them, so
// that large messages' handshakes go on while the rows are summed.
void ForceEvaluation::compute_overlapping_refresh(const ForceContext& context, bool sample) {
    constexpr std::size_t kPokes = 8;
    decomp::HaloExchange& halo = near_.halo();
    const NeighbourList& list = near_.list();
    const std::size_t n_interior = near_.n_interior();
    ForceContext rows = context;
    const std::size_t stages = halo.refresh_stages(), pieces = stages * kPokes;
    for (std::size_t k = 0; k < pieces; ++k) {
        rows.first = n_interior * k / pieces;
        rows.last = n_interior * (k + 1) / pieces;
        terms_.front()->add_forces(s_.store, list, rows, sample, sums_);
        if ((k + 1) % kPokes == 0)
            halo.advance_refresh();
        else
            halo.progress();
    }
    halo.end_refresh();
    near_.refresh_done();
    rows.first = n_interior;
    rows.last = static_cast<std::size_t>(-1);
    terms_.front()->add_forces(s_.store, list, rows, sample, sums_);
    for (std::size_t k = 1; k < terms_.size(); ++k) terms_[k]->add_forces(s_.store, list, context, sample, sums_);
}

}  // namespace emergent

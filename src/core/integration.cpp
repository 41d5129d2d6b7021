// SPDX-License-Identifier: MIT
#include "core/integration.hpp"

#include <cmath>
#include <vector>

#include "decomposition/reductions.hpp"
#include "emergent/execution.hpp"
#include "integrate/kick_drift.hpp"
#include "integrate/particle_sums.hpp"

namespace emergent {
namespace {

/// What the thermostat acting before a kick-drift needs, measured in its pass: the kinetic
/// energy and squared drift of the velocities it starts from, then the kick-drift, then the
/// displacement since the list was built.
struct MeasuredKickDrift {
    integrate::KickDrift stage;
    integrate::FreeKineticEnergy kinetic;
    SquaredDisplacement moved;
    EMERGENT_HD integrate::DriftMeasures operator()(std::size_t i) const {
        const double before = kinetic(i);
        const Vec3 v = stage.v[i];
        stage(i);
        return {before, moved(i), double(stage.drift) * double(stage.drift) * dot(v, v)};
    }
};

}  // namespace

void Integration::kick_drift(double kick, double drift, double at, bool step_start) {
    PhaseTimer timer(s_.times.integrate);
    ParticleStore& store = s_.store;
    near_.note_moved();
    s_.particles.backend_reads(kPosition | kVelocity | kForce | kSpecies);
    const integrate::KickDrift stage{s_.data(kPosition, store.position), s_.data(kVelocity, store.velocity),
                                     s_.data(kForce, store.force),       s_.data(kSpecies, store.species),
                                     s_.inverse_masses(),                kick,
                                     drift};
    // Where the drift is the last move before the rebuild test, the test is taken in the same
    // pass: one read of the positions fewer, and on a device one launch fewer.
    // With the thermostat acting before it (see integration.hpp), its measures too.
    const Vec3* x0 = s_.boundaries.empty() && !s_.bodies() ? near_.check_origin() : nullptr;
    if (x0 && thermostat && step_start && !(s_.ghost_fields & kVelocity)) {
        const integrate::DriftMeasures m = exec::transform_sum<integrate::DriftMeasures>(
            s_.target, store.n_owned(), MeasuredKickDrift{stage, s_.kinetic_energy(), {stage.x, x0}});
        near_.drift_moved(m.moved_sq);
        voted_ = true;
        drift_kinetic_ = m.kinetic;
        drift_step_sq_ = m.step_sq;
        voted_kick_ = kick;
        voted_drift_ = drift;
    } else if (x0) {
        near_.drift_moved(exec::transform_max(
            s_.target, store.n_owned(), 0.0,
            exec::Then<integrate::KickDrift, SquaredDisplacement>{stage, {stage.x, x0}}));
    } else {
        exec::for_each(s_.target, store.n_owned(), stage);
    }
    s_.particles.backend_wrote(kPosition | kVelocity);
    // Spheres of bodies were moved as free particles above; the bodies now place them.
    if (s_.bodies()) {
        s_.rigid.kick_drift(s_.target,
                            s_.body_arrays(kPosition | kVelocity | kForce | kSpecies | kOrientation |
                                           kAngularMomentum | kTorque),
                            s_.data(kPosition, store.position), s_.data(kVelocity, store.velocity), kick, drift);
        s_.bodies_resident.backend_wrote(kPosition | kVelocity | kOrientation | kAngularMomentum);
        s_.particles.backend_wrote(kPosition | kVelocity);
    }
    if (s_.boundaries.empty()) return;
    s_.particles.backend_reads(kPosition | kVelocity | kSpecies | kId);
    const BackendParticles particles = forces_.backend_particles();
    const BoundaryContext context{drift, s_.step, &s_.box, at};
    for (auto& rule : s_.boundaries) rule->apply(particles, context, s_.boundary_fault);
    s_.particles.backend_wrote(kPosition | kVelocity);
}

void Integration::kick(double kick) {
    PhaseTimer timer(s_.times.integrate);
    ParticleStore& store = s_.store;
    s_.particles.backend_reads(kVelocity | kForce | kSpecies);
    const integrate::Kick stage{s_.data(kVelocity, store.velocity), s_.data(kForce, store.force),
                                s_.data(kSpecies, store.species), s_.inverse_masses(), kick};
    // The thermostat that follows at the step's end needs the kinetic energy: summed in the
    // same pass.
    if (thermostat && !s_.bodies() && !thermostat_done_) {
        kick_kinetic_ = exec::transform_sum<double>(
            s_.target, store.n_owned(), exec::Then<integrate::Kick, integrate::FreeKineticEnergy>{stage, s_.kinetic_energy()});
        kick_kinetic_known_ = true;
    } else {
        exec::for_each(s_.target, store.n_owned(), stage);
    }
    s_.particles.backend_wrote(kVelocity);
    if (s_.bodies()) {
        // The step's Langevin pass sets the constituents' velocities again before anything
        // reads them (the thermostat reads the free particles' alone).
        s_.rigid.kick(s_.target,
                      s_.body_arrays(kPosition | kVelocity | kForce | kSpecies | kOrientation | kAngularMomentum |
                                     kTorque),
                      s_.data(kPosition, store.position), s_.data(kVelocity, store.velocity), kick, !body_langevin);
        s_.bodies_resident.backend_wrote(kVelocity | kAngularMomentum);
        s_.particles.backend_wrote(kVelocity);
    }
}

Integration::VoteSums Integration::vote_sums() const {
    if (!voted_) return {};
    return {true, drift_kinetic_, drift_step_sq_};
}

double Integration::apply_voted_thermostat(const VoteSums& total) {
    if (!voted_) return 0;
    voted_ = false;
    PhaseTimer timer(s_.times.integrate);
    ParticleStore& store = s_.store;
    const double factor = thermostat->scale_factor(total.kinetic, s_.dof(), s_.step, s_.settings.dt);
    s_.particles.backend_reads(kPosition | kVelocity | kForce | kSpecies);
    exec::for_each(s_.target, store.n_owned(),
                   integrate::RescaleBeforeKickDrift{s_.data(kPosition, store.position), s_.data(kVelocity, store.velocity),
                                                     s_.data(kForce, store.force), s_.data(kSpecies, store.species),
                                                     s_.inverse_masses(), voted_kick_, voted_drift_, factor - 1});
    s_.particles.backend_wrote(kPosition | kVelocity);
    thermostat_done_ = true;
    return std::fabs(factor - 1);
}

void Integration::apply_thermostat() {
    if (!thermostat) return;
    if (thermostat_done_) {
        thermostat_done_ = false;
        return;
    }
    PhaseTimer timer(s_.times.integrate);
    if (s_.bodies()) {
        thermostat_free_particles();
        return;
    }
    const double local = kick_kinetic_known_ ? kick_kinetic_ : s_.local_kinetic();
    kick_kinetic_known_ = false;
    double kinetic;
    {
        PhaseTimer summing(s_.times.collective_wait, s_.after_build_slot());
        kinetic = decomp::sum(s_.comm, local);
    }
    const double factor = thermostat->scale_factor(kinetic, s_.dof(), s_.step, s_.settings.dt);
    exec::for_each(s_.target, s_.store.n_owned(), integrate::ScaleVelocity{s_.data(kVelocity, s_.store.velocity), factor});
    s_.particles.backend_wrote(kVelocity);
}

/// With rigid bodies the thermostat acts on the free particles alone (an explicit solvent bath),
/// about their mean velocity; the bodies take the bath's temperature through collisions only.
void Integration::thermostat_free_particles() {
    const ParticleStore& store = s_.store;
    s_.particles.backend_reads(kVelocity | kSpecies | kBody);
    const integrate::MassMotion local = exec::transform_sum<integrate::MassMotion>(
        s_.target, store.n_owned(),
        integrate::FreeMassMotion{s_.data(kVelocity, store.velocity), s_.data(kSpecies, store.species), s_.masses(),
                                  s_.data(kBody, store.body)});
    double sums[5] = {local.mass, local.kinetic, local.momentum.x, local.momentum.y, local.momentum.z};
    {
        PhaseTimer summing(s_.times.collective_wait, s_.after_build_slot());
        exec::count_collective();
        MPI_Allreduce(MPI_IN_PLACE, sums, 5, MPI_DOUBLE, MPI_SUM, s_.comm);
    }
    if (s_.n_free < 2 || !(sums[0] > 0)) return;
    const Vec3 momentum{sums[2], sums[3], sums[4]};
    const double relative = sums[1] - 0.5 * dot(momentum, momentum) / sums[0];
    const double factor = thermostat->scale_factor(relative, 3.0 * double(s_.n_free) - 3.0, s_.step, s_.settings.dt);
    exec::for_each(s_.target, store.n_owned(),
                   integrate::ScaleFreeAboutMean{s_.data(kVelocity, store.velocity), s_.data(kBody, store.body),
                                                 (1 / sums[0]) * momentum, factor});
    s_.particles.backend_wrote(kVelocity);
}

void Integration::apply_body_langevin() {
    if (!body_langevin || !s_.bodies()) return;
    PhaseTimer timer(s_.times.integrate);
    s_.particles.backend_reads(kPosition | kVelocity);
    const double dt = s_.settings.dt;
    s_.rigid.langevin(s_.target,
                      s_.body_arrays(kPosition | kVelocity | kSpecies | kId | kOrientation | kAngularMomentum),
                      s_.data(kPosition, s_.store.position), s_.data(kVelocity, s_.store.velocity),
                      std::exp(-body_langevin->translation_rate * dt), std::exp(-body_langevin->rotation_rate * dt),
                      body_langevin->temperature, body_langevin->seed, static_cast<std::uint64_t>(s_.step));
    s_.bodies_resident.backend_wrote(kVelocity | kAngularMomentum);
    s_.particles.backend_wrote(kVelocity);
}

void Integration::apply_wall_layers() {
    if (wall_layers.empty()) return;
    PhaseTimer timer(s_.times.integrate);
    s_.particles.backend_reads(kPosition | kVelocity | kSpecies);
    const BackendParticles particles = forces_.backend_particles();
    // The layers due now are measured first and summed in one collective, where no two share
    // a particle (each then rescales what the others did not touch: the same as one after the
    // other).
    std::vector<WallLayerThermostat*> due;
    for (auto& layer : wall_layers)
        if (layer->due(s_.step)) due.push_back(layer.get());
    bool apart = true;
    for (std::size_t a = 0; a < due.size(); ++a)
        for (std::size_t b = a + 1; b < due.size(); ++b) apart = apart && !due[a]->overlaps(*due[b]);
    if (!apart) {
        for (WallLayerThermostat* layer : due) layer->apply(particles, s_.comm, s_.step);
    } else if (!due.empty()) {
        std::vector<double> sums(due.size() * WallLayerThermostat::kSums);
        for (std::size_t k = 0; k < due.size(); ++k) due[k]->measure(particles, &sums[k * WallLayerThermostat::kSums]);
        decomp::sum_in_place(s_.comm, sums.data(), static_cast<int>(sums.size()));
        for (std::size_t k = 0; k < due.size(); ++k) due[k]->rescale(particles, &sums[k * WallLayerThermostat::kSums]);
    }
    s_.particles.backend_wrote(kVelocity);
}

}  // namespace emergent

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

/// A stage, then its particle's kinetic energy and displacement, in one pass.
template <class Stage, class Kinetic, class Moved>
struct MeasuredStage {
    Stage stage;
    Kinetic kinetic;
    Moved moved;
    EMERGENT_HD integrate::KineticAndMoved operator()(std::size_t i) const {
        stage(i);
        return {kinetic(i), moved(i)};
    }
};

}  // namespace

void Integration::kick_drift(double kick, double drift, double at, bool thermostat_next) {
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
    // The thermostat that may follow needs the kinetic energy: summed in the same pass too.
    if (const Vec3* x0 = s_.boundaries.empty() && !s_.bodies() ? near_.check_origin() : nullptr) {
        if (thermostat && thermostat_next) {
            const integrate::KineticAndMoved measured = exec::transform_sum<integrate::KineticAndMoved>(
                s_.target, store.n_owned(),
                MeasuredStage<integrate::KickDrift, integrate::FreeKineticEnergy, SquaredDisplacement>{
                    stage, s_.kinetic_energy(), {stage.x, x0}});
            near_.drift_moved(measured.moved_sq);
            drift_kinetic_ = measured.kinetic;
            drift_kinetic_known_ = true;
        } else {
            near_.drift_moved(exec::transform_max(
                s_.target, store.n_owned(), 0.0,
                exec::Then<integrate::KickDrift, SquaredDisplacement>{stage, {stage.x, x0}}));
        }
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
                                s_.data(kSpecies, store.species), s_.inverse_masses(), kick, kick_scale_};
    kick_scale_ = 1;
    exec::for_each(s_.target, store.n_owned(), stage);
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

Integration::HalfStepSums Integration::half_step_sums() {
    HalfStepSums local;
    PhaseTimer timer(s_.times.integrate);
    if (thermostat && s_.bodies()) {
        const ParticleStore& store = s_.store;
        s_.particles.backend_reads(kVelocity | kSpecies | kBody);
        const integrate::MassMotion m = exec::transform_sum<integrate::MassMotion>(
            s_.target, store.n_owned(),
            integrate::FreeMassMotion{s_.data(kVelocity, store.velocity), s_.data(kSpecies, store.species),
                                      s_.masses(), s_.data(kBody, store.body)});
        local = {{m.mass, m.kinetic, m.momentum.x, m.momentum.y, m.momentum.z}, 5};
    } else if (thermostat) {
        local.values[0] = drift_kinetic_known_ ? drift_kinetic_ : s_.local_kinetic();
        local.n = 1;
    }
    drift_kinetic_known_ = false;
    // The wall layers due at the step being completed (keyed by its index, as at its end).
    voted_layers_.clear();
    layers_voted_ = false;
    if (thermostat || wall_layers.empty()) return local;
    for (auto& layer : wall_layers)
        if (layer->due(s_.step + 1)) voted_layers_.push_back(layer.get());
    bool fit = local.n + int(voted_layers_.size()) * WallLayerThermostat::kSums <= Neighbourhood::kMaxVoteSums;
    for (std::size_t a = 0; a < voted_layers_.size(); ++a)
        for (std::size_t b = a + 1; b < voted_layers_.size(); ++b) fit = fit && !voted_layers_[a]->overlaps(*voted_layers_[b]);
    if (!fit) {
        voted_layers_.clear();
        return local;
    }
    layers_voted_ = true;
    s_.particles.backend_reads(kPosition | kVelocity | kSpecies);
    const BackendParticles particles = forces_.backend_particles();
    for (WallLayerThermostat* layer : voted_layers_) {
        layer->measure(particles, local.values + local.n);
        local.n += WallLayerThermostat::kSums;
    }
    return local;
}

void Integration::apply_half_step(const HalfStepSums& total) {
    PhaseTimer timer(s_.times.integrate);
    if (layers_voted_ && !voted_layers_.empty()) {
        const BackendParticles particles = forces_.backend_particles();
        const double* sums = total.values;
        for (WallLayerThermostat* layer : voted_layers_) {
            layer->rescale(particles, sums);
            sums += WallLayerThermostat::kSums;
        }
        s_.particles.backend_wrote(kVelocity);
    }
    if (!thermostat) return;
    if (s_.bodies()) {
        thermostat_free_particles(total.values);
        return;
    }
    const double factor = thermostat->scale_factor(total.values[0], s_.dof(), s_.step, s_.settings.dt);
    // Where nothing reads velocities before the kick (no velocity-dependent force, no ghost
    // velocities), the kick applies the factor in its pass.
    if (!(s_.ghost_fields & kVelocity)) {
        kick_scale_ = factor;
        return;
    }
    exec::for_each(s_.target, s_.store.n_owned(), integrate::ScaleVelocity{s_.data(kVelocity, s_.store.velocity), factor});
    s_.particles.backend_wrote(kVelocity);
}

/// With rigid bodies the thermostat acts on the free particles alone (an explicit solvent bath),
/// about their mean velocity; the bodies take the bath's temperature through collisions only.
void Integration::thermostat_free_particles(const double* sums) {
    const ParticleStore& store = s_.store;
    if (s_.n_free < 2 || !(sums[0] > 0)) return;
    const Vec3 momentum{sums[2], sums[3], sums[4]};
    const double relative = sums[1] - 0.5 * dot(momentum, momentum) / sums[0];
    const double factor = thermostat->scale_factor(relative, 3.0 * double(s_.n_free) - 3.0, s_.step, s_.settings.dt);
    s_.particles.backend_reads(kVelocity | kBody);
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
    if (wall_layers.empty() || layers_voted_) {
        layers_voted_ = false;  // done at the half step, in the vote
        return;
    }
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

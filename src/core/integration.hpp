// SPDX-License-Identifier: MIT
// The moves of a step: kicks and drifts of free particles and bodies (the walls act on each
// drift), the thermostat, the bodies' Langevin bath and the wall layers.
//
// The thermostat acts after the step's last drift, on the half-step velocities, so that its
// sums travel in the rebuild vote's collective: a step waits for the other ranks once. A global
// rescaling placed there is a splitting of the same dynamics as one at the step's end (the
// velocity Verlet step, then the thermostat's), as GROMACS's leap-frog couples its
// thermostats at the half step.
#pragma once
#include <memory>
#include <optional>
#include <vector>

#include "core/engine_state.hpp"
#include "core/force_evaluation.hpp"
#include "core/neighbourhood.hpp"
#include "emergent/thermostat.hpp"
#include "emergent/wall_layer.hpp"

namespace emergent {

class Integration {
public:
    Integration(EngineState& state, Neighbourhood& neighbourhood, ForceEvaluation& forces)
        : s_(state), near_(neighbourhood), forces_(forces) {}

    /// v += kick f/m, x += drift v; then the walls act on the drift (at time `at`).
    /// `thermostat_next`: the thermostat acts after this drift, so its kinetic energy is
    /// summed in the same pass where it can be.
    void kick_drift(double kick, double drift, double at, bool thermostat_next = false);
    /// v = s v + kick f/m, where s is the thermostat's factor if it was left to this kick
    /// (otherwise 1).
    void kick(double kick);
    /// What the thermostat and the wall layers need from every rank after the step's last
    /// drift, this rank's part (summed in Neighbourhood::vote): the thermostat's kinetic energy
    /// (with rigid bodies the free particles' mass, kinetic energy and momentum); without a
    /// thermostat, the sums of the wall layers due at the step being completed, where they
    /// share no particle and fit (else they act at the step's end, apply_wall_layers).
    struct HalfStepSums {
        double values[Neighbourhood::kMaxVoteSums] = {};
        int n = 0;
    };
    HalfStepSums half_step_sums();
    /// From the sums over all ranks: the wall layers rescale their particles; the thermostat's
    /// factor is applied now where the forces or the ghosts read velocities (or bodies are
    /// present), else left to the next kick.
    void apply_half_step(const HalfStepSums& total);
    void apply_body_langevin();
    /// Keyed by the step just completed.
    void apply_wall_layers();

    std::unique_ptr<Thermostat> thermostat;
    std::optional<BodyLangevinSettings> body_langevin;
    std::vector<std::unique_ptr<WallLayerThermostat>> wall_layers;

private:
    void thermostat_free_particles(const double* sums);

    EngineState& s_;
    Neighbourhood& near_;
    ForceEvaluation& forces_;
    /// This rank's free kinetic energy, summed in the last drift's pass for the thermostat.
    double drift_kinetic_ = 0;
    bool drift_kinetic_known_ = false;
    /// The thermostat's factor, left to the next kick.
    double kick_scale_ = 1;
    /// The wall layers measured in this step's vote, rescaled after it.
    std::vector<WallLayerThermostat*> voted_layers_;
    bool layers_voted_ = false;
};

}  // namespace emergent

// SPDX-License-Identifier: MIT
// The moves of a step: kicks and drifts of free particles and bodies (the walls act on each
// drift), the thermostat, the bodies' Langevin bath and the wall layers.
//
// The thermostat acts on whole-step velocities between steps. Where it can (velocity Verlet,
// no walls or bodies, no force reading velocities), it acts at the start of the step and its
// kinetic energy, summed in the kick-drift's pass, travels in the rebuild vote's collective: a
// step waits for the other ranks once, and the factor is applied after the drift as if before
// it (integrate::RescaleBeforeKickDrift). Elsewhere it acts at the step's end with its own
// global sum.
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
    /// `step_start`: this kick-drift starts the step (velocity Verlet's), so the thermostat
    /// may act before it (see above).
    void kick_drift(double kick, double drift, double at, bool step_start = false);
    /// v += kick f/m.
    void kick(double kick);
    /// What the thermostat acting before this step's kick-drift needs from every rank (this
    /// rank's kinetic energy) and the largest squared drift of those velocities (to bound the
    /// displacement the rescaling adds); none where it acts at the step's end.
    struct VoteSums {
        bool present = false;  ///< the thermostat acts in this step's vote
        double kinetic = 0, step_sq = 0;
    };
    VoteSums vote_sums() const;
    /// From the sums over all ranks: the thermostat's factor applied to the velocities the
    /// kick-drift started from. Returns |factor - 1|: the drift's displacement grows by at most
    /// that times sqrt(step_sq).
    double apply_voted_thermostat(const VoteSums& total);
    /// The thermostat at the step's end, where it did not act in the vote (own global sum).
    void apply_thermostat();
    void apply_body_langevin();
    /// Keyed by the step just completed.
    void apply_wall_layers();

    std::unique_ptr<Thermostat> thermostat;
    std::optional<BodyLangevinSettings> body_langevin;
    std::vector<std::unique_ptr<WallLayerThermostat>> wall_layers;

private:
    void thermostat_free_particles();

    EngineState& s_;
    Neighbourhood& near_;
    ForceEvaluation& forces_;
    /// This step's kick-drift measured the velocities it started from for the thermostat: their
    /// kinetic energy, their largest squared drift, and the kick's and drift's durations.
    bool voted_ = false;
    double drift_kinetic_ = 0, drift_step_sq_ = 0, voted_kick_ = 0, voted_drift_ = 0;
    /// The thermostat acted in this step's vote: not again at its end.
    bool thermostat_done_ = false;
    /// This rank's free kinetic energy, summed in the last kick's pass for the thermostat at
    /// the step's end.
    double kick_kinetic_ = 0;
    bool kick_kinetic_known_ = false;
};

}  // namespace emergent

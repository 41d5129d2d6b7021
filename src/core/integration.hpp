// SPDX-License-Identifier: MIT
// The moves of a step: kicks and drifts of free particles and bodies (the walls act on each
// drift), the thermostat, the bodies' Langevin bath and the wall layers.
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
    void kick_drift(double kick, double drift, double at);
    /// v += kick f/m.
    void kick(double kick);
    void apply_thermostat();
    void apply_body_langevin();
    /// Keyed by the step just completed.
    void apply_wall_layers();

    std::unique_ptr<Thermostat> thermostat;
    std::optional<BodyLangevinSettings> body_langevin;
    std::vector<std::unique_ptr<WallLayerThermostat>> wall_layers;

private:
    void thermostat_free_particles();
    /// Where this step rebuilt the list, the slot its first global sum's wait also goes to.
    double* after_build_wait() { return near_.built_this_step() ? &s_.times.collective_wait_after_build : nullptr; }

    EngineState& s_;
    Neighbourhood& near_;
    ForceEvaluation& forces_;
    /// This rank's free kinetic energy, summed in the last kick's pass for the thermostat.
    double kick_kinetic_ = 0;
    bool kick_kinetic_known_ = false;
};

}  // namespace emergent

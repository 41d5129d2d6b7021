// SPDX-License-Identifier: MIT
// The engine behind Simulation: its shared state and its parts, each with one job.
#pragma once
#include "core/engine_state.hpp"
#include "core/force_evaluation.hpp"
#include "core/integration.hpp"
#include "core/neighbourhood.hpp"
#include "emergent/simulation.hpp"

namespace emergent {

struct Simulation::Engine : EngineState {
    Neighbourhood neighbourhood{*this};
    ForceEvaluation forces{*this, neighbourhood};
    Integration motion{*this, neighbourhood, forces};
    MessageTraffic traffic_at_reset;  ///< the counters when the measured phase began
    double wait_at_reset = 0;

    /// Sets up the list and cells for the force terms present, and counts particles.
    void prepare();
};

}  // namespace emergent

// SPDX-License-Identifier: MIT
// Run-time guards: stop a run that went unstable, keeping its last good state.
#pragma once

#include "emergent/config.hpp"
#include "emergent/simulation.hpp"

namespace emergent::app {

/// Checks the state every `guard.every` steps (finite positions, velocities and forces; forces
/// below `guard.max_force`) and, in NVE runs, the total energy per particle against the first
/// sample (`guard.max_energy_drift`). After each passed check it keeps a snapshot of the
/// state, so a failed run can be saved at its last good step. Failures throw InstabilityError
/// on every rank.
class RunGuard {
public:
    RunGuard(const Config& config, const Simulation& sim);

    /// Runs the state checks if due (or if `now`), then remembers the state as good.
    void after_step(const Simulation& sim, bool now = false);
    /// Energy-drift check at a sample (NVE only).
    void on_sample(const Simulation& sim, const ThermoSample& t);

    /// The last state that passed the checks; null when none was kept (guard.every = 0 and no
    /// checkpoint yet).
    const StateSnapshot* last_good() const { return have_good_ ? &last_good_ : nullptr; }

private:
    GuardLimits limits_;
    long long every_ = 0;
    double max_drift_ = 0, reference_energy_ = 0, max_overlap_ = 0;
    bool have_reference_ = false, have_good_ = false;
    StateSnapshot last_good_;
};

}  // namespace emergent::app

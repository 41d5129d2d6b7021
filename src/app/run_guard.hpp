// SPDX-License-Identifier: MIT
// Run-time guards: stop a run that went unstable, keeping its last good state.
#pragma once

#include "emergent/config.hpp"
#include "emergent/problem.hpp"
#include "emergent/simulation.hpp"

namespace emergent::app {

/// Checks the state every `guard.every` steps (finite positions, velocities and forces; forces
/// below `guard.max_force`) and, in NVE runs, the total energy per particle against the first
/// sample (`guard.max_energy_drift`). After each passed check it keeps a snapshot of the
/// state, so a failed run can be saved at its last good step. Failures throw InstabilityError
/// on every rank.
class RunGuard {
public:
    /// `keep_state`: copy the good states (only worth their memory, 64-112 bytes a particle,
    /// when the run has a directory to save the last one in); otherwise only their step is
    /// remembered. `scene` (may be null): its running state (Problem::saved_state) is kept
    /// with each good state, so the saved one continues as a checkpoint does.
    RunGuard(const Config& config, const Simulation& sim, bool keep_state, const Problem* scene = nullptr);

    /// Runs the state checks if due (or if `now`), then remembers the state as good.
    void after_step(const Simulation& sim, bool now = false);
    /// Energy-drift check at a sample (NVE only).
    void on_sample(const Simulation& sim, const ThermoSample& t);

    /// The last state that passed the checks; null when none was kept (guard.every = 0 and no
    /// checkpoint yet, or no state is kept).
    const StateSnapshot* last_good() const { return have_good_ && keep_state_ ? &last_good_ : nullptr; }
    /// The scene's running state at the last good step (empty without a scene).
    const Measures& last_good_scene_state() const { return scene_state_; }
    /// Step of the last state that passed the checks; -1 when none did yet.
    long long last_good_step() const { return have_good_ ? good_step_ : -1; }

private:
    void keep(const Simulation& sim);

    GuardLimits limits_;
    long long every_ = 0;
    double max_drift_ = 0, reference_energy_ = 0, max_overlap_ = 0;
    bool have_reference_ = false, have_good_ = false;
    long long good_step_ = -1;
    bool keep_state_ = true;
    StateSnapshot last_good_;
    const Problem* scene_ = nullptr;
    Measures scene_state_;
};

}  // namespace emergent::app

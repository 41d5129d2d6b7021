// SPDX-License-Identifier: MIT
// Run-time guards.
#include "app/run_guard.hpp"

#include <cmath>
#include <sstream>

#include "emergent/error.hpp"

namespace emergent::app {

RunGuard::RunGuard(const Config& config, const Simulation& sim, bool keep_state, const Problem* scene)
    : keep_state_(keep_state), scene_(scene) {
    limits_.max_force = config.real("guard.max_force");
    every_ = config.integer("guard.every");
    max_drift_ = sim.conserves_energy() ? config.real("guard.max_energy_drift") : 0.0;
    max_overlap_ = config.real("guard.max_overlap");
    // A bad start has no good state to fall back to: report it as it is.
    sim.check_guards(limits_);
    // Keeping the last good state costs a partial copy of the owned particles (64-112 B each,
    // StateSnapshot); guard.every = 0 keeps none between checkpoints.
    if (every_ > 0) keep(sim);
}

void RunGuard::after_step(const Simulation& sim, bool now) {
    if (!now && (every_ <= 0 || sim.step_index() % every_ != 0)) return;
    sim.check_guards(limits_);
    keep(sim);
}

void RunGuard::keep(const Simulation& sim) {
    // Without a place to save it the state is not copied: its step is all that is reported.
    if (keep_state_) {
        sim.snapshot(last_good_);
        if (scene_) scene_state_ = scene_->saved_state();
    }
    good_step_ = sim.step_index();
    have_good_ = true;
}

void RunGuard::on_sample(const Simulation& sim, const ThermoSample& t) {
    if (max_overlap_ > 0 && t.max_overlap > max_overlap_) {
        std::ostringstream msg;
        msg << "granular contacts overlap by " << t.max_overlap << " sphere diameters at step "
            << sim.step_index() << ", beyond guard.max_overlap=" << max_overlap_
            << " (time step too large for k_n, or particles driven into each other?)";
        throw InstabilityError(msg.str());
    }
    if (max_drift_ <= 0) return;
    if (!have_reference_) {
        reference_energy_ = t.total;
        have_reference_ = true;
        return;
    }
    // Written so that a NaN energy fails too.
    if (!(std::abs(t.total - reference_energy_) <= max_drift_)) {
        std::ostringstream msg;
        msg << "total energy per particle drifted from " << reference_energy_ << " to " << t.total
            << " by step " << sim.step_index() << ", beyond guard.max_energy_drift=" << max_drift_
            << " (NVE run: time step too large for this state?)";
        throw InstabilityError(msg.str());
    }
}

}  // namespace emergent::app

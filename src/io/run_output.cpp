// SPDX-License-Identifier: MIT
// Run output: trajectory frames and observables.
#include "io/run_output.hpp"

#include <algorithm>
#include <sstream>

#include "emergent/error.hpp"

namespace emergent::io {

std::vector<std::string> parse_elements(const std::string& scene, const std::string& text) {
    std::vector<std::string> items;
    std::stringstream in(text);
    std::string item;
    const auto& known = H5mdWriter::known_elements();
    while (std::getline(in, item, ',')) {
        item.erase(std::remove(item.begin(), item.end(), ' '), item.end());
        if (item.empty()) continue;
        if (std::find(known.begin(), known.end(), item) == known.end())
            throw InputError(scene + ": output.elements has unknown element '" + item +
                             "' (known: position, velocity, species, id, image)");
        items.push_back(item);
    }
    return items;
}

RunOutput::RunOutput(const std::string& dir, const Config& config, Simulation& sim) {
    every_ = config.integer("output.every");
    const auto elements = parse_elements(config.scene(), config.text("output.elements"));
    if (dir.empty()) return;
    H5mdMetadata meta;
    meta.config = &config;
    meta.box = sim.box();
    meta.n_global = sim.n_global();
    meta.elements = elements;
    trajectory_ = std::make_unique<H5mdWriter>(dir + "/trajectory.h5", sim.comm(), meta);
}

RunOutput::~RunOutput() = default;

void RunOutput::on_sample(const ThermoSample& t) {
    if (!trajectory_) return;
    trajectory_->write_observable("kinetic_energy", t.step, t.time, {t.kinetic});
    trajectory_->write_observable("potential_energy", t.step, t.time, {t.potential});
    trajectory_->write_observable("total_energy", t.step, t.time, {t.total});
    trajectory_->write_observable("temperature", t.step, t.time, {t.temperature});
    trajectory_->write_observable("pressure", t.step, t.time, {t.pressure});
    trajectory_->write_observable("momentum", t.step, t.time,
                                  {t.momentum.x, t.momentum.y, t.momentum.z});
}

void RunOutput::on_step(Simulation& sim) {
    if (!trajectory_) return;
    const long long step = sim.step_index();
    const bool due = last_frame_ < 0 || (every_ > 0 && step % every_ == 0);
    if (!due || step == last_frame_) return;
    trajectory_->write_particles(sim.particles(), step, sim.time());
    last_frame_ = step;
}

void RunOutput::finish(Simulation& sim) {
    if (!trajectory_) return;
    if (sim.step_index() != last_frame_)
        trajectory_->write_particles(sim.particles(), sim.step_index(), sim.time());
    trajectory_->finish();
    trajectory_.reset();
}

}  // namespace emergent::io

// SPDX-License-Identifier: MIT
// Builds a scene's Simulation from `key=value` settings, as `emergent run` would.
#pragma once

#include <mpi.h>

#include <memory>
#include <string>
#include <vector>

#include "app/run.hpp"
#include "emergent/problem.hpp"
#include "emergent/simulation.hpp"

namespace emergent::testing {

inline Config scene_config(const std::string& scene, const std::vector<std::string>& sets,
                           const std::string& preset = "") {
    const ProblemInfo* info = ProblemRegistry::instance().find(scene);
    if (!info) throw std::logic_error("no scene " + scene);
    return resolve_config(*info, preset, {}, sets);
}

/// A built and initialised simulation of `scene` on `comm`.
inline std::unique_ptr<Simulation> make_scene(MPI_Comm comm, const std::string& scene,
                                              const std::vector<std::string>& sets) {
    const Config config = scene_config(scene, sets);
    RunSettings settings;
    settings.dt = config.real("dt");
    settings.skin = config.real("skin");
    settings.grid = app::parse_grid(scene, config.text("grid"));
    auto sim = std::make_unique<Simulation>(comm, settings);
    auto problem = ProblemRegistry::instance().find(scene)->factory(config);
    problem->build(*sim);
    problem->place_particles(*sim);
    sim->initialise();
    return sim;
}

inline bool relative_close(double a, double b, double tolerance) {
    const double scale = std::max({std::abs(a), std::abs(b), 1e-300});
    return std::abs(a - b) <= tolerance * scale;
}

}  // namespace emergent::testing

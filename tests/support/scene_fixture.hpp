// SPDX-License-Identifier: MIT
// Builds a scene's Simulation from `key=value` settings, as `emergent run` would.
#pragma once

#include <mpi.h>

#include <map>
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

/// A scene, built and initialised, with its problem kept (for its field grids and measures).
struct BuiltScene {
    std::unique_ptr<Problem> problem;
    std::unique_ptr<Simulation> sim;
};

inline BuiltScene build_scene(MPI_Comm comm, const std::string& scene,
                              const std::vector<std::string>& sets, const std::string& preset = "") {
    const Config config = scene_config(scene, sets, preset);
    BuiltScene s;
    s.sim = std::make_unique<Simulation>(comm, app::run_settings(config));
    s.problem = ProblemRegistry::instance().find(scene)->factory(config);
    s.problem->build(*s.sim);
    s.problem->place_particles(*s.sim);
    s.sim->initialise();
    return s;
}

/// A built and initialised simulation of `scene` on `comm`.
inline std::unique_ptr<Simulation> make_scene(MPI_Comm comm, const std::string& scene,
                                              const std::vector<std::string>& sets,
                                              const std::string& preset = "") {
    return build_scene(comm, scene, sets, preset).sim;
}

/// (id -> position) of every particle on every rank. Collective.
inline std::map<std::int64_t, Vec3> gather_positions(const Simulation& sim) {
    const ParticleStore& s = sim.particles();
    std::vector<double> mine;
    for (std::size_t i = 0; i < s.n_owned(); ++i)
        mine.insert(mine.end(), {double(s.id[i]), s.position[i].x, s.position[i].y, s.position[i].z});
    int n = static_cast<int>(mine.size()), ranks = 1;
    MPI_Comm_size(sim.comm(), &ranks);
    std::vector<int> counts(ranks), offsets(ranks, 0);
    MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, sim.comm());
    for (int r = 1; r < ranks; ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
    std::vector<double> all(offsets.back() + counts.back());
    MPI_Allgatherv(mine.data(), n, MPI_DOUBLE, all.data(), counts.data(), offsets.data(),
                   MPI_DOUBLE, sim.comm());
    std::map<std::int64_t, Vec3> out;
    for (std::size_t k = 0; k < all.size(); k += 4)
        out[static_cast<std::int64_t>(all[k])] = {all[k + 1], all[k + 2], all[k + 3]};
    return out;
}

inline bool relative_close(double a, double b, double tolerance) {
    const double scale = std::max({std::abs(a), std::abs(b), 1e-300});
    return std::abs(a - b) <= tolerance * scale;
}

}  // namespace emergent::testing

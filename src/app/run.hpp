// SPDX-License-Identifier: MIT
// Runs one scene: build, equilibrate, measure, report.
#pragma once

#include <mpi.h>

#include <string>

#include "emergent/config.hpp"
#include "emergent/problem.hpp"
#include "emergent/simulation.hpp"
#include "emergent/vec3.hpp"
#include "io/checkpoint.hpp"

namespace emergent::app {

struct RunRequest {
    const ProblemInfo* problem = nullptr;
    Config config;
    std::string output_dir;    ///< empty: no files besides the summary
    std::string summary_json;  ///< empty: none
    std::string restart_file;  ///< checkpoint to continue from
    bool overwrite = false;    ///< replace an earlier run in output_dir (--overwrite)
    const io::CheckpointHeader* restart = nullptr;
};

/// Runs the scene on `comm`; progress goes to stdout on rank 0. Returns the summary as JSON.
std::string run_problem(const RunRequest& request, MPI_Comm comm);

/// Parses "NXxNYxNZ" or "auto" (0x0x0).
Int3 parse_grid(const std::string& scene, const std::string& text);

/// The engine settings a scene's configuration names (dt, skin, integrator, rank grid).
RunSettings run_settings(const Config& cfg);

}  // namespace emergent::app

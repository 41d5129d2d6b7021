// SPDX-License-Identifier: MIT
// Everything a run records into its output directory, driven by the run loop.
#pragma once

#include <memory>
#include <string>

#include "emergent/config.hpp"
#include "emergent/simulation.hpp"
#include "io/h5md_writer.hpp"

namespace emergent::io {

/// Writes DIR/trajectory.h5 (H5MD): particle frames every `output.every` steps (0: first and
/// last only) and the thermodynamic observables at every sample. Inactive when dir is empty.
class RunOutput {
public:
    RunOutput(const std::string& dir, const Config& config, Simulation& sim);
    ~RunOutput();

    /// Records the observables of a sample.
    void on_sample(const ThermoSample& t);
    /// Writes a particle frame if this step is due.
    void on_step(Simulation& sim);
    /// Writes the last frame (unless just written) and marks the file complete.
    void finish(Simulation& sim);

private:
    std::unique_ptr<H5mdWriter> trajectory_;
    long long every_ = 0, last_frame_ = -1;
};

/// Splits "a,b,c" into its items (spaces ignored); throws InputError for unknown items.
std::vector<std::string> parse_elements(const std::string& scene, const std::string& text);

}  // namespace emergent::io

// SPDX-License-Identifier: MIT
// Checkpoints: everything needed to continue a run exactly, in one HDF5 file.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "emergent/config.hpp"
#include "emergent/problem.hpp"
#include "emergent/simulation.hpp"
#include "observe/field_accumulator.hpp"

namespace emergent::io {

/// What a checkpoint says about the run besides its particles.
struct CheckpointHeader {
    std::string scene;
    std::map<std::string, std::string> config;  ///< every resolved parameter
    long long step = 0, rebuilds = 0, n_global = 0;
    double time = 0;
    int ranks = 0;                              ///< rank count that wrote it
    std::vector<double> box;                    ///< lo, hi, periodic flags, wedge (empty: not kept)
    std::vector<double> domain_grid;            ///< ranks per axis that wrote it (empty: not kept)
    std::vector<double> domain_cuts;            ///< Simulation::domain_cuts() at the save
    std::vector<ThermoSample> series;           ///< samples of the measured phase so far
    /// Field intervals in progress: grid name -> (global sums, samples).
    std::map<std::string, std::pair<std::vector<double>, long long>> fields;
    /// Simulation::exchange_tallies() at the checkpoint (wall exchanges, wall-layer energies).
    std::vector<double> exchange_tallies;
    /// Problem::saved_state() at the checkpoint.
    std::map<std::string, std::vector<double>> scene_state;
};

/// Writes the state of `sim` to `path` atomically (path.tmp, then rename). Collective.
void write_checkpoint(const std::string& path, Simulation& sim, const Config& config,
                      const std::vector<ThermoSample>& series,
                      const std::vector<FieldAccumulator>& fields,
                      const Measures& scene_state = {});

/// Reads the header; InputError if the file is missing, truncated or not a checkpoint.
CheckpointHeader read_checkpoint_header(const std::string& path, MPI_Comm comm);

/// Loads the particles into `sim` (box, forces and species already built) and continues the
/// run at the saved step, on any rank count. Collective.
void restore_checkpoint(const std::string& path, Simulation& sim, const CheckpointHeader& header);

}  // namespace emergent::io

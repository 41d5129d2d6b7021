// SPDX-License-Identifier: MIT
// The summary of a run (JSON) and its plain-text time series.
#pragma once

#include <string>
#include <vector>

#include "emergent/config.hpp"
#include "emergent/problem.hpp"
#include "emergent/simulation.hpp"

namespace emergent::app {

/// Machine-readable summary: sizes, timing of the measured phase (atom-steps/s over
/// `timed_steps`), block-averaged T, P, U with standard errors, energy drift, phase times
/// (slowest rank) and peak memory (summed over ranks). `series[0]` is the state the measured
/// phase started from; the averages use the later samples; `scene_measures` are the scene's
/// own measures at the end. Collective.
std::string summary_json(const Simulation& sim, const Config& cfg,
                         const std::vector<ThermoSample>& series, double wall,
                         long long timed_steps, const Measures& scene_measures = {});

/// One line per sample: step time T P kinetic potential total px py pz.
std::string thermo_table(const std::vector<ThermoSample>& series);

}  // namespace emergent::app

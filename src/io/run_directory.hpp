// SPDX-License-Identifier: MIT
// A run's output directory: what the engine writes there, named once, so that a directory
// holding one run is never silently replaced by another or left mixing two.
#pragma once

#include <string>
#include <vector>

namespace emergent::io {

/// Whether `name` (a file name without its directory) is one the engine writes into a run's
/// output directory: trajectory and field files with their continued segments
/// (trajectory.from<STEP>.h5) and XDMF sidecars, thermo.dat, summary.json, snapshot.h5,
/// checkpoint.h5, last_good.h5, and the .tmp files these are written through.
bool is_run_output(const std::string& name);

/// The engine's files in `dir`, sorted; empty when there are none or `dir` does not exist.
std::vector<std::string> run_outputs_in(const std::string& dir);

/// Removes those files (the user's own files stay). Throws IoError naming the file and the
/// system's reason when one cannot be removed.
void remove_run_outputs(const std::string& dir);

/// Whether the H5MD trajectory at `path` was closed by a run that finished its segment
/// (`emergent_complete` = 1). A missing or unreadable file is not complete.
bool trajectory_complete(const std::string& path);

/// "a, b, c" of at most `shown` names, then "and N more".
std::string list_names(const std::vector<std::string>& names, std::size_t shown = 4);

}  // namespace emergent::io

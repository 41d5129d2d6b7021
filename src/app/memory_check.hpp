// SPDX-License-Identifier: MIT
// Refuses a run that cannot fit in its nodes' memory, before it allocates.
#pragma once

#include <mpi.h>

#include <string>
#include <vector>

#include "emergent/field_grid.hpp"

namespace emergent::app {

/// Bytes each particle needs at least: its fields in the particle store, twice (the store and
/// the guards' last good state). The measured peak is 2-3x this (neighbour lists, ghosts, sort
/// buffers: benchmarks/results/host_speed.md), so a run refused here could never have run.
double particle_bytes_lower_bound();

/// Memory of this node as far as this process may use it: the smaller of the machine's total
/// and the control group's limit, in bytes (0: unknown).
double node_memory_bytes();

/// Throws InputError when `particles` (over all ranks) and the field `grids` need more than the
/// memory of the nodes the ranks of `comm` run on, each node holding its ranks' share.
/// `what` names the parameters that set the particle count, `scene` the scene.
void check_memory(MPI_Comm comm, const std::string& scene, double particles,
                  const std::string& what, const std::vector<FieldGrid>& grids);

}  // namespace emergent::app

// SPDX-License-Identifier: MIT
// Everything a run records into its output directory, driven by the run loop.
#pragma once

#include <memory>
#include <string>

#include "emergent/config.hpp"
#include "emergent/problem.hpp"
#include "emergent/simulation.hpp"
#include "io/checkpoint.hpp"
#include "io/field_writer.hpp"
#include "io/h5md_writer.hpp"
#include "io/watch_snapshot.hpp"
#include "observe/field_accumulator.hpp"

namespace emergent::io {

/// Writes DIR/trajectory.h5 (H5MD): particle frames every `output.every` steps (0: first and
/// last only) and the thermodynamic observables at every sample; and, when `fields.interval`
/// > 0, coarse-grained fields averaged over each interval into DIR/fields.h5 + fields.xmf; and,
/// every `output.snapshot_seconds` of wall time, DIR/snapshot.h5 for watching (WatchSnapshot).
/// Inactive (and costs nothing) when dir is empty.
class RunOutput {
public:
    /// grids: the scene's own field grids (the box grid of `fields.grid` is added here).
    /// A run continued from a checkpoint (sim.step_index() > 0 at construction) writes
    /// trajectory.from<step>.h5 and fields.from<step>.h5, never overwriting the files of the
    /// run it continues.
    /// `scene` (may be null) analyses the field frames of its own grids.
    RunOutput(const std::string& dir, const Config& config, Simulation& sim,
              std::vector<FieldGrid> grids, Problem* scene = nullptr);
    ~RunOutput();

    /// Records the observables of a sample, and the scene's measures taken with it.
    void on_sample(const ThermoSample& t, const Measures& scene_measures = {});
    /// Writes a particle frame if this step is due.
    void on_step(Simulation& sim);
    /// Writes the last frame (unless just written) and marks the file complete.
    void finish(Simulation& sim);

    /// Field accumulators (empty when fields are off), for checkpoints.
    const std::vector<FieldAccumulator>& fields() const { return fields_; }
    /// Continues the field intervals a checkpoint had in progress.
    void restore_fields(const CheckpointHeader& checkpoint, int rank);

private:
    /// A frame of the rigid bodies, with the scene's per-body values.
    void write_bodies(Simulation& sim);
    /// A particle frame (and the bodies') of this step.
    void write_frame(Simulation& sim);

    std::string trajectory_path_, fields_path_;
    std::unique_ptr<H5mdWriter> trajectory_;
    long long every_ = 0, last_frame_ = -1;
    // Coarse-grained fields: accumulated on every rank, written by rank 0.
    std::vector<FieldAccumulator> fields_;
    std::unique_ptr<FieldWriter> field_writer_;
    long long field_interval_ = 0, field_sample_every_ = 1, last_field_step_ = -1;
    bool first_step_seen_ = false;
    Problem* scene_ = nullptr;
    std::unique_ptr<WatchSnapshot> snapshot_;  // rank 0 only
    /// For the destructor alone: whether every rank is unwinding from the same error.
    MPI_Comm unwinding_ = MPI_COMM_NULL;
    static constexpr double kUnwindWaitSeconds = 5.0;
};

/// Splits "a,b,c" into its items (spaces ignored); throws InputError for unknown items.
std::vector<std::string> parse_elements(const std::string& scene, const std::string& text);

/// The run's box-wide field grid from `fields.grid` ("NXxNYxNZ"); InputError naming it.
FieldGrid parse_box_grid(const std::string& scene, const std::string& text, const Box& box);

}  // namespace emergent::io

// SPDX-License-Identifier: MIT
// Run output: trajectory frames and observables.
#include "io/run_output.hpp"

#include <algorithm>
#include <cerrno>
#include <exception>
#include <sstream>
#include <utility>

#include "decomposition/ranks_meet.hpp"
#include "emergent/error.hpp"

namespace emergent::io {

namespace {
/// Runs `write`; an I/O failure in it names the file it was writing.
template <class Write>
void writing(const std::string& path, Write&& write) {
    errno = 0;  // a cause found afterwards is this write's, not an earlier probe's
    try {
        write();
    } catch (const IoError& e) {
        throw IoError("cannot write '" + path + "': " + e.what());
    }
}
}  // namespace

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
                             "' (known: position, velocity, species, id, image, diameter)");
        items.push_back(item);
    }
    return items;
}

FieldGrid parse_box_grid(const std::string& scene, const std::string& text, const Box& box) {
    FieldGrid g;
    if (!parse_counts(text, g.n))
        throw InputError(scene + ": fields.grid=" + text + " must be NXxNYxNZ, e.g. 1x1x20");
    if (double(g.n.x) * double(g.n.y) * double(g.n.z) > 2147483647.0)
        throw InputError(scene + ": fields.grid=" + text + " has more than 2^31 cells");
    g.name = "box";
    g.lo = box.lo;
    g.hi = box.hi;
    return g;
}

RunOutput::RunOutput(const std::string& dir, const Config& config, Simulation& sim,
                     std::vector<FieldGrid> grids, Problem* scene)
    : scene_(scene) {
    every_ = config.integer("output.every");
    const auto elements = parse_elements(config.scene(), config.text("output.elements"));
    field_interval_ = config.integer("fields.interval");
    field_sample_every_ = config.integer("fields.sample_every");
    grids.insert(grids.begin(), parse_box_grid(config.scene(), config.text("fields.grid"), sim.box()));
    if (dir.empty()) return;
    const std::string suffix =
        sim.step_index() > 0 ? ".from" + std::to_string(sim.step_index()) : std::string();
    if (field_interval_ > 0) {
        for (const FieldGrid& g : grids) fields_.emplace_back(g);
        fields_path_ = dir + "/fields" + suffix + ".h5";
        if (sim.rank() == 0)
            field_writer_ = std::make_unique<FieldWriter>(dir, "fields" + suffix, grids);
    }
    if (sim.rank() == 0)
        snapshot_ = std::make_unique<WatchSnapshot>(dir, config.scene(), grids,
                                                    config.real("output.snapshot_seconds"));
    H5mdMetadata meta;
    meta.config = &config;
    meta.box = sim.box();
    meta.n_global = sim.n_global();
    meta.n_bodies = sim.has_bodies() ? sim.n_bodies_global() : 0;
    meta.elements = elements;
    trajectory_path_ = dir + "/trajectory" + suffix + ".h5";
    writing(trajectory_path_, [&] {
        trajectory_ = std::make_unique<H5mdWriter>(trajectory_path_, sim.comm(), meta);
    });
    if (sim.n_ranks() > 1) MPI_Comm_dup(sim.comm(), &unwinding_);
}

RunOutput::~RunOutput() {
    if (unwinding_ == MPI_COMM_NULL) return;
    // Closing the trajectory is collective. Left by an error that only this rank met (an
    // internal fault in the middle of a step), the other ranks wait in the step's next
    // collective and never come: closing would hang the job. The file is then left open
    // (what was flushed stays) and the failure report ends the job.
    if (std::uncaught_exceptions() > 0 && !decomp::ranks_meet(unwinding_, kUnwindWaitSeconds)) {
        (void)trajectory_.release();
        return;
    }
    MPI_Comm_free(&unwinding_);
}

void RunOutput::on_sample(const ThermoSample& t, const Measures& scene_measures) {
    if (!trajectory_) return;
    writing(trajectory_path_, [&] {
        for (const auto& [name, value] : scene_measures)
            trajectory_->write_observable(name, t.step, t.time, value);
        trajectory_->write_observable("kinetic_energy", t.step, t.time, {t.kinetic});
        trajectory_->write_observable("potential_energy", t.step, t.time, {t.potential});
        trajectory_->write_observable("total_energy", t.step, t.time, {t.total});
        trajectory_->write_observable("temperature", t.step, t.time, {t.temperature});
        trajectory_->write_observable("pressure", t.step, t.time, {t.pressure});
        trajectory_->write_observable("momentum", t.step, t.time,
                                      {t.momentum.x, t.momentum.y, t.momentum.z});
        if (t.max_overlap >= 0)
            trajectory_->write_observable("max_overlap", t.step, t.time, {t.max_overlap});
        // A killed run keeps its series up to the last sample (particle frames may be rare).
        trajectory_->flush();
    });
    if (snapshot_) {
        snapshot_->on_measures(t.step, t.time, scene_measures);
        snapshot_->on_measures(t.step, t.time,
                               {{"temperature", {t.temperature}}, {"total_energy", {t.total}},
                                {"pressure", {t.pressure}}});
        snapshot_->maybe_write(t.step, t.time);
    }
}

void RunOutput::on_step(Simulation& sim) {
    if (!trajectory_) return;
    const long long step = sim.step_index();
    // Frame k averages samples in (step_k - interval, step_k]: the state a run starts from
    // is not sampled, and neither is a step seen twice.
    const bool fresh_step = step > last_field_step_;
    last_field_step_ = std::max(last_field_step_, step);
    if (!fields_.empty() && fresh_step && first_step_seen_ && step % field_sample_every_ == 0)
        for (FieldAccumulator& f : fields_) f.add_sums(std::as_const(sim).field_sums(f.grid()));
    first_step_seen_ = true;
    if (!fields_.empty() && step % field_interval_ == 0 && fields_.front().samples() > 0) {
        for (std::size_t g = 0; g < fields_.size(); ++g) {
            const FieldFrame frame = fields_[g].take(sim.comm());
            if (field_writer_)
                writing(fields_path_, [&] { field_writer_->write(g, step, sim.time(), frame); });
            if (snapshot_) snapshot_->on_fields(g, frame);
            if (scene_ && g > 0) {  // grid 0 is the run's box grid, the others the scene's
                const Measures found = scene_->analyse_fields(fields_[g].grid(), frame);
                writing(trajectory_path_, [&] {
                    for (const auto& [name, value] : found)
                        trajectory_->write_observable(name, step, sim.time(), value);
                });
                if (snapshot_) snapshot_->on_measures(step, sim.time(), found);
            }
        }
        writing(trajectory_path_, [&] { trajectory_->flush(); });
        if (snapshot_) snapshot_->maybe_write(step, sim.time());
    }
    const bool due = last_frame_ < 0 || (every_ > 0 && step % every_ == 0);
    if (!due || step == last_frame_) return;
    write_frame(sim);
}

void RunOutput::write_frame(Simulation& sim) {
    writing(trajectory_path_, [&] {
        trajectory_->write_particles(std::as_const(sim).particles(), sim.step_index(), sim.time());
        if (sim.has_bodies()) write_bodies(sim);
    });
    last_frame_ = sim.step_index();
}

void RunOutput::write_bodies(Simulation& sim) {
    // The scene's values first: they may sync the bodies, whose arrays are then read once.
    const Measures extra = scene_ ? scene_->body_frame_values(sim) : Measures{};
    trajectory_->write_bodies(std::as_const(sim).bodies(), sim.step_index(), sim.time(), extra);
}

void RunOutput::restore_fields(const CheckpointHeader& checkpoint, int rank) {
    for (FieldAccumulator& f : fields_) {
        const auto it = checkpoint.fields.find(f.grid().name);
        if (it != checkpoint.fields.end()) f.restore(it->second.first, it->second.second, rank);
    }
}

void RunOutput::finish(Simulation& sim) {
    if (!trajectory_) return;
    if (sim.step_index() != last_frame_) write_frame(sim);
    writing(trajectory_path_, [&] { trajectory_->finish(); });
    trajectory_.reset();
    if (snapshot_) snapshot_->maybe_write(sim.step_index(), sim.time(), true);
}

}  // namespace emergent::io

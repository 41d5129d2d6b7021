// SPDX-License-Identifier: MIT
// The run loop of a scene and its summary.
#include "app/run.hpp"


#include <algorithm>
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "decomposition/reductions.hpp"
#include "emergent/device_profile.hpp"
#include "emergent/error.hpp"
#include "emergent/gpu.hpp"
#include "emergent/simulation.hpp"
#include "io/atomic_file.hpp"
#include "io/checkpoint.hpp"
#include "io/run_directory.hpp"
#include "io/run_output.hpp"
#include "app/memory_check.hpp"
#include "app/run_guard.hpp"
#include "app/run_summary.hpp"
#include "app/stop_request.hpp"

namespace emergent::app {

namespace {
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// One line every `interval` wall seconds, printed by rank 0 only.
class ProgressLine {
public:
    /// `first`: the step the run starts from (a continued run counts its rate from there).
    ProgressLine(double interval, long long first, long long total, bool printer)
        : interval_(interval), first_(first), total_(total), printer_(printer),
          start_(Clock::now()), last_(start_) {}

    /// The line carries the scene's progress note (Problem::progress_note) after the time.
    void maybe_print(const ThermoSample& t, const char* phase, const Problem& problem,
                     const Measures& measures) {
        if (!printer_ || interval_ <= 0 || seconds_since(last_) < interval_) return;
        last_ = Clock::now();
        const double rate = (t.step - first_) / std::max(1e-9, seconds_since(start_));
        const double eta = (total_ - t.step) / std::max(1e-9, rate);
        const std::string note = problem.progress_note(measures);
        std::printf("step %lld/%lld %s  t=%.3f%s%s  %.3g steps/s  ETA %.0fs  T=%.5f  E/N=%.6f\n",
                    t.step, total_, phase, t.time, note.empty() ? "" : "  ", note.c_str(), rate,
                    eta, t.temperature, t.total);
        std::fflush(stdout);
    }

private:
    double interval_;
    long long first_, total_;
    bool printer_;
    Clock::time_point start_, last_;
};



/// Returns the run to its last good state and saves it as DIR/last_good.h5; says where.
std::string save_last_good(Simulation& sim, const RunGuard& guard, const Config& cfg,
                           std::vector<ThermoSample> series, const std::string& dir) {
    if (guard.last_good_step() < 0) return "no good state was kept (guard.every=0)";
    const std::string at = "last good state at step " + std::to_string(guard.last_good_step());
    const StateSnapshot* good = guard.last_good();
    if (dir.empty() || !good) return at + " (run with -o DIR to keep it as a checkpoint)";
    sim.restore(*good);
    while (!series.empty() && series.back().step > good->step) series.pop_back();
    io::write_checkpoint(dir + "/last_good.h5", sim, cfg, series, {}, guard.last_good_scene_state());
    return at + " saved in " + dir + "/last_good.h5";
}
}  // namespace

Int3 parse_grid(const std::string& scene, const std::string& text) {
    if (text == "auto") return {0, 0, 0};
    Int3 g{0, 0, 0};
    if (!parse_counts(text, g))
        throw InputError(scene + ": grid=" + text + " must be 'auto' or NXxNYxNZ, e.g. 2x1x1");
    return g;
}

RunSettings run_settings(const Config& cfg) {
    RunSettings settings;
    settings.dt = cfg.real("dt");
    settings.skin = cfg.real("skin");
    settings.cell_subdivisions = static_cast<int>(cfg.integer("cell_subdivisions"));
    settings.integrator =
        cfg.text("integrator") == "omelyan" ? Integrator::Omelyan : Integrator::VelocityVerlet;
    settings.grid = parse_grid(cfg.scene(), cfg.text("grid"));
    const std::string& backend = cfg.text("backend");
    // auto: the device where this build has CUDA and the process sees one (the CUDA back end
    // passed benchmarks/gpu_check.sh on an H200, benchmarks/results/gpu.md), else the host.
    settings.backend = backend == "cuda"       ? Backend::Cuda
                       : backend == "checking" ? Backend::Checking
                       : backend == "host"     ? Backend::Host
                       : gpu::device_present() ? Backend::Cuda
                                               : Backend::Host;
    const std::string& layout = cfg.text("neighbour_list");
    settings.list_layout = layout == "full"   ? ListLayout::Full
                           : layout == "half" ? ListLayout::Half
                                              : ListLayout::Auto;
    settings.balance = cfg.text("balance") == "cost" ? LoadBalance::Cost : LoadBalance::None;
    settings.balance_every = cfg.integer("balance.every");
    settings.equilibration_steps = cfg.integer("equilibration_steps");
    settings.overlap_halo = cfg.text("halo_overlap") == "on";
    const std::string& direct = cfg.text("mpi_direct");
    settings.mpi_direct = direct == "on" ? MpiDirect::On : direct == "off" ? MpiDirect::Off : MpiDirect::Auto;
    settings.interior_order = cfg.text("halo_overlap") == "ordered";
    return settings;
}

namespace {

namespace fs = std::filesystem;

/// What is wrong with writing this run into its output directory (empty: nothing). Asked on
/// one rank, before the run spends any time or touches a file. Sets `replace` when the
/// directory holds an earlier run that --overwrite replaces.
std::string output_dir_problem(const RunRequest& req, bool& replace) {
    const std::string& dir = req.output_dir;
    std::error_code ec;
    const std::string from = req.restart ? fs::path(req.restart_file).parent_path().string() : "";
    const bool continuing = req.restart && fs::equivalent(dir, from.empty() ? "." : from, ec);
    if (continuing) {
        if (req.overwrite)
            return "--overwrite would remove the checkpoint this run continues from ('" +
                   req.restart_file + "'): continue without it, or write elsewhere with -o DIR";
        // A continuation writes trajectory.from<STEP>.h5; one from the same step that ran to
        // its end is a whole file that a second continuation would replace.
        const std::string segment =
            dir + "/trajectory.from" + std::to_string(req.restart->step) + ".h5";
        if (io::trajectory_complete(segment))
            return "-o " + dir + ": '" + segment + "' is a finished continuation from step " +
                   std::to_string(req.restart->step) + "; continuing again from that step " +
                   "would replace it: move it away first, or continue with -o ANOTHER_DIR";
        return "";
    }
    const std::vector<std::string> earlier = io::run_outputs_in(dir);
    if (!earlier.empty()) {
        if (req.overwrite) {
            replace = true;
            return "";
        }
        const bool resumable = fs::exists(dir + "/checkpoint.h5", ec);
        return "-o " + dir + ": the directory holds an earlier run (" + io::list_names(earlier) +
               "); give --overwrite to replace it" +
               (resumable ? ", or continue it with --restart " + dir + "/checkpoint.h5" : "") +
               ", or choose another directory";
    }
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir)) return "cannot create output directory '" + dir + "'";
    return "";
}

/// Checks the output directory on rank 0, and creates it; every rank learns the verdict.
/// Returns whether the earlier run there is to be removed (once set-up has succeeded).
bool claim_output_dir(const RunRequest& req, MPI_Comm comm) {
    if (req.output_dir.empty()) return false;
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    bool replace = false;
    const std::string problem =
        decomp::first_message(comm, rank == 0 ? output_dir_problem(req, replace) : "");
    if (!problem.empty()) throw InputError(problem);
    int flag = replace;
    MPI_Bcast(&flag, 1, MPI_INT, 0, comm);
    return flag != 0;
}

/// --overwrite: the earlier run's files go before this run writes its first one, so the
/// directory never holds both.
void remove_earlier_run(const std::string& dir, MPI_Comm comm) {
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    std::string failure;
    if (rank == 0) {
        try {
            io::remove_run_outputs(dir);
        } catch (const IoError& e) {
            failure = e.what();
        }
    }
    failure = decomp::first_message(comm, failure);
    if (!failure.empty()) throw IoError(failure);
}

/// The summary file must be writable before the run spends its time: a run that cannot report
/// is refused at the start.
void check_summary_path(const std::string& path, MPI_Comm comm) {
    if (path.empty()) return;
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    int failed = 0;
    if (rank == 0) {
        const std::string probe = path + ".tmp";
        std::FILE* f = std::fopen(probe.c_str(), "w");
        failed = f == nullptr;
        if (f) std::fclose(f), std::remove(probe.c_str());
    }
    MPI_Bcast(&failed, 1, MPI_INT, 0, comm);
    if (failed) throw InputError("--summary-json: cannot write '" + path + "'");
}

/// Steps from wherever the simulation is to the end of the run. Steps are counted globally
/// (0 .. n_eq + n_steps), so a continued run takes the same sampling, output and checkpoint
/// decisions as an uninterrupted one. Returns the wall time of the measured phase. A stop asked
/// for by a signal (StopRequest) ends the loop early with a checkpoint of that step, and sets
/// `stopped_by` to the signal.
double advance(Simulation& sim, Problem& problem, const RunRequest& req, io::RunOutput& output,
               std::vector<ThermoSample>& series, Measures& last_measures,
               StopRequest& stop_request, int& stopped_by) {
    const Config& cfg = req.config;
    const long long n_eq = cfg.integer("equilibration_steps");
    const long long end = n_eq + cfg.integer("steps");
    const long long every = cfg.integer("sample_every");
    const long long checkpoint_every = cfg.integer("checkpoint_every");
    ProgressLine progress(cfg.real("progress_interval"), sim.step_index(), end, sim.rank() == 0);
    auto sample_due = [&](long long s) { return s % every == 0 || s == n_eq || s == end; };
    const long long observe_every = problem.observe_every();
    if (sim.step_index() == n_eq && series.empty()) {
        problem.on_equilibrated(sim);
        series.push_back(sim.measure());
    }
    RunGuard guard(cfg, sim, !req.output_dir.empty(), &problem);
    sim.reset_phase_times();
    Clock::time_point t0 = Clock::now();
    try {
        while (sim.step_index() < end) {
            if (sim.step_index() == n_eq) {  // the measured phase starts: time it alone
                sim.reset_phase_times();
                t0 = Clock::now();
            }
            const long long s = sim.step_index() + 1;
            const bool stop = stop_request.agreed();
            const bool checkpoint = (checkpoint_every > 0 && s % checkpoint_every == 0) || stop;
            sim.step(sample_due(s));
            if (s == n_eq) problem.on_equilibrated(sim);
            // Sampled bounds (energy drift, overlaps) are checked before this step's state may
            // become the last good one.
            ThermoSample t;
            if (sample_due(s)) {
                t = sim.measure();
                guard.on_sample(sim, t);
            }
            guard.after_step(sim, checkpoint);  // a checkpoint is only written from a good state
            output.on_step(sim);
            if (observe_every > 0 && s % observe_every == 0) problem.observe(sim);
            if (sample_due(s)) {
                last_measures = problem.measures(sim);
                output.on_sample(t, last_measures);
                if (s >= n_eq) series.push_back(t);
                progress.maybe_print(t, s <= n_eq ? "(equilibration)" : "", problem,
                                     last_measures);
            }
            if (checkpoint)
                io::write_checkpoint(req.output_dir + "/checkpoint.h5", sim, cfg, series,
                                     output.fields(), problem.saved_state());
            if (stop) {
                stopped_by = stop_request.signal();
                break;
            }
        }
    } catch (const InstabilityError& e) {
        throw InstabilityError(std::string(e.what()) + "; " +
                               save_last_good(sim, guard, cfg, series, req.output_dir));
    }
    return decomp::max(sim.comm(), seconds_since(t0));
}

}  // namespace

std::string run_problem(const RunRequest& req, MPI_Comm comm) {
    const Config& cfg = req.config;
    if (cfg.integer("checkpoint_every") > 0 && req.output_dir.empty())
        throw InputError(cfg.scene() + ": checkpoint_every needs an output directory (-o DIR)");
    const bool replace_earlier = claim_output_dir(req, comm);
    check_summary_path(req.summary_json, comm);
    // From here SIGUSR1 and SIGTERM ask for a checkpoint at the first step it can be written
    // (Ctrl-C from the end of the set-up on).
    StopRequest stop_request(comm, !req.output_dir.empty());

    Simulation sim(comm, run_settings(cfg));
    auto problem = req.problem->factory(cfg);
    // A scene whose build() holds every particle is refused before it, where it can tell.
    if (!req.restart) {
        const ParticleEstimate early = problem->particles_from_parameters();
        if (early.count >= 0) check_memory(comm, cfg.scene(), early.count, early.set_by, {});
    }
    problem->build(sim);
    // Too large for the nodes' memory: refused before particles and grids are allocated.
    std::vector<FieldGrid> grids;  // allocated only when fields are recorded
    if (cfg.integer("fields.interval") > 0 && !req.output_dir.empty()) {
        grids = problem->field_grids(sim);
        grids.push_back(io::parse_box_grid(cfg.scene(), cfg.text("fields.grid"), sim.box()));
    }
    const ParticleEstimate estimate =
        req.restart ? ParticleEstimate{double(req.restart->n_global), "the checkpoint's particles"}
                    : problem->expected_particles(sim);
    check_memory(comm, cfg.scene(), std::max(0.0, estimate.count), estimate.set_by, grids);
    std::vector<ThermoSample> series;  // samples of the measured phase
    if (req.restart) {
        io::restore_checkpoint(req.restart_file, sim, *req.restart);
        // Checkpoints from before tallies were kept continue with tallies from zero.
        if (!req.restart->exchange_tallies.empty())
            sim.restore_exchange_tallies(req.restart->exchange_tallies);
        problem->restore_state(req.restart->scene_state);
        series = req.restart->series;
        // A run that ended off the sampling grid sampled its last step, which the run continued
        // here would not have sampled: that row goes, so the rows and averages are the
        // uninterrupted run's.
        const long long every = cfg.integer("sample_every"), n_eq = cfg.integer("equilibration_steps"),
                        end = n_eq + cfg.integer("steps");
        series.erase(std::remove_if(series.begin(), series.end(),
                                    [&](const ThermoSample& t) {
                                        return t.step % every != 0 && t.step != n_eq && t.step != end;
                                    }),
                     series.end());
    } else {
        problem->place_particles(sim);
        // Bodies place their spheres only at initialise(): count the bodies meanwhile.
        const long long placed = decomp::sum(
            comm, static_cast<long long>(sim.particles().n_owned() +
                                         (sim.has_bodies() ? sim.bodies().n_owned() : 0)));
        if (placed == 0)
            throw InputError(cfg.scene() + ": these parameters place no particles" +
                             (estimate.set_by.empty() ? "" : " (" + estimate.set_by + ")"));
        // A scene that could not tell its count beforehand is checked before lists and ghosts.
        if (estimate.count < 0) check_memory(comm, cfg.scene(), double(placed), "", grids);
        sim.initialise();
    }
    stop_request.catch_interrupt();
    if (replace_earlier) remove_earlier_run(req.output_dir, comm);
    io::RunOutput output(req.output_dir, cfg, sim, problem->field_grids(sim), problem.get());
    if (req.restart) output.restore_fields(*req.restart, sim.rank());
    output.on_step(sim);

    const long long n_eq = cfg.integer("equilibration_steps");
    const long long timed_steps = n_eq + cfg.integer("steps") - std::max(sim.step_index(), n_eq);
    Measures last_measures;
    int stopped_by = 0;
    const double wall = advance(sim, *problem, req, output, series, last_measures, stop_request,
                                stopped_by);
    output.finish(sim);
    if (stopped_by != 0) {
        const std::string& dir = req.output_dir;
        throw RunStopped("stopped on request (" + signal_name(stopped_by) + ") at step " +
                         std::to_string(sim.step_index()) + " of " +
                         std::to_string(n_eq + cfg.integer("steps")) + "; checkpoint " + dir +
                         "/checkpoint.h5; continue with: emergent run --restart " + dir +
                         "/checkpoint.h5 -o " + dir);
    }
    if (series.empty()) series.push_back(sim.measure());
    if (last_measures.empty()) last_measures = problem->measures(sim);

    const std::string json = summary_json(sim, cfg, series, wall, timed_steps, last_measures);
    if (sim.rank() == 0) {
        // One closing line a person can read; the full summary is in the JSON.
        const ThermoSample& last = series.back();
        std::printf("%s: N=%lld on %d rank(s), at step %lld; measured %lld steps in %.3g s "
                    "(%.3g atom-steps/s); final T=%.4f P=%.4f U/N=%.4f (averages: summary JSON)"
                    "%s%s\n",
                    cfg.scene().c_str(), sim.n_global(), sim.n_ranks(), sim.step_index(),
                    timed_steps, wall, wall > 0 ? sim.n_global() * double(timed_steps) / wall : 0.0,
                    last.temperature, last.pressure, last.potential,
                    req.output_dir.empty() ? "" : "; output in ", req.output_dir.c_str());
        std::fflush(stdout);
        if (!req.output_dir.empty()) {
            io::write_atomically(req.output_dir + "/thermo.dat", thermo_table(series));
            io::write_atomically(req.output_dir + "/summary.json", json);
        }
        if (!req.summary_json.empty()) io::write_atomically(req.summary_json, json);
        // Set-up, equilibration and timed steps together (EMERGENT_PROFILE; rank 0's device).
        if (exec::profiling()) std::fputs(exec::profile_table().c_str(), stderr);
    }
    return json;
}

}  // namespace emergent::app

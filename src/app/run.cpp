// SPDX-License-Identifier: MIT
// The run loop of a scene and its summary.
#include "app/run.hpp"

#include <sys/resource.h>

#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "decomposition/reductions.hpp"
#include "emergent/error.hpp"
#include "emergent/simulation.hpp"
#include "io/atomic_file.hpp"
#include "io/checkpoint.hpp"
#include "io/run_output.hpp"
#include "app/run_guard.hpp"
#include "observe/block_average.hpp"

namespace emergent::app {

namespace {
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// One line every `interval` wall seconds, printed by rank 0 only.
class ProgressLine {
public:
    ProgressLine(double interval, long long total, bool printer)
        : interval_(interval), total_(total), printer_(printer), start_(Clock::now()),
          last_(start_) {}

    void maybe_print(const ThermoSample& t, const char* phase) {
        if (!printer_ || interval_ <= 0 || seconds_since(last_) < interval_) return;
        last_ = Clock::now();
        const double rate = t.step / std::max(1e-9, seconds_since(start_));
        const double eta = (total_ - t.step) / std::max(1e-9, rate);
        std::printf("step %lld/%lld %s  t=%.3f  %.3g steps/s  ETA %.0fs  T=%.5f  E/N=%.6f\n",
                    t.step, total_, phase, t.time, rate, eta, t.temperature, t.total);
        std::fflush(stdout);
    }

private:
    double interval_;
    long long total_;
    bool printer_;
    Clock::time_point start_, last_;
};

/// Least-squares slope of total energy per particle against time.
double drift_rate(const std::vector<ThermoSample>& s) {
    if (s.size() < 2) return 0;
    double mt = 0, me = 0;
    for (const auto& x : s) mt += x.time, me += x.total;
    mt /= s.size();
    me /= s.size();
    double num = 0, den = 0;
    for (const auto& x : s) num += (x.time - mt) * (x.total - me), den += (x.time - mt) * (x.time - mt);
    return den > 0 ? num / den : 0;
}

std::string json_number(double v) {
    if (!std::isfinite(v)) return "null";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.12g", v);
    return buf;
}

long long peak_rss_bytes_of_rank() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return static_cast<long long>(usage.ru_maxrss) * 1024;  // Linux reports kilobytes
}
/// Returns the run to its last good state and saves it as DIR/last_good.h5; says where.
std::string save_last_good(Simulation& sim, const StateSnapshot& good, const Config& cfg,
                           std::vector<ThermoSample> series, const std::string& dir) {
    const std::string at = "last good state at step " + std::to_string(good.step);
    if (dir.empty()) return at + " (run with -o DIR to keep it as a checkpoint)";
    sim.restore(good);
    while (!series.empty() && series.back().step > good.step) series.pop_back();
    io::write_checkpoint(dir + "/last_good.h5", sim, cfg, series, {});
    return at + " saved in " + dir + "/last_good.h5";
}
}  // namespace

Int3 parse_grid(const std::string& scene, const std::string& text) {
    if (text == "auto") return {0, 0, 0};
    Int3 g{0, 0, 0};
    char x1 = 0, x2 = 0, extra = 0;
    std::istringstream in(text);
    if (!(in >> g.x >> x1 >> g.y >> x2 >> g.z) || x1 != 'x' || x2 != 'x' || (in >> extra) ||
        g.x < 1 || g.y < 1 || g.z < 1)
        throw InputError(scene + ": grid=" + text + " must be 'auto' or NXxNYxNZ, e.g. 2x1x1");
    return g;
}

std::string run_problem(const RunRequest& req, MPI_Comm comm) {
    const Config& cfg = req.config;
    RunSettings settings;
    settings.dt = cfg.real("dt");
    settings.skin = cfg.real("skin");
    settings.grid = parse_grid(cfg.scene(), cfg.text("grid"));
    const long long checkpoint_every = cfg.integer("checkpoint_every");
    if (checkpoint_every > 0 && req.output_dir.empty())
        throw InputError(cfg.scene() + ": checkpoint_every needs an output directory (-o DIR)");
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    if (!req.output_dir.empty()) {
        std::error_code ec;
        if (rank == 0) std::filesystem::create_directories(req.output_dir, ec);
        int failed = ec ? 1 : 0;
        MPI_Bcast(&failed, 1, MPI_INT, 0, comm);
        if (failed) throw InputError("cannot create output directory '" + req.output_dir + "'");
    }

    Simulation sim(comm, settings);
    auto problem = req.problem->factory(cfg);
    problem->build(sim);
    std::vector<ThermoSample> series;  // samples of the measured phase
    if (req.restart) {
        io::restore_checkpoint(req.restart_file, sim, *req.restart);
        series = req.restart->series;
    } else {
        problem->place_particles(sim);
        sim.initialise();
    }
    io::RunOutput output(req.output_dir, cfg, sim, problem->field_grids(sim));
    if (req.restart) output.restore_fields(*req.restart, rank);
    output.on_step(sim);

    // Steps are counted globally (0 .. n_eq + n_steps), so a continued run takes the same
    // sampling, output and checkpoint decisions as an uninterrupted one.
    const long long n_eq = cfg.integer("equilibration_steps");
    const long long n_steps = cfg.integer("steps");
    const long long end = n_eq + n_steps;
    const long long every = cfg.integer("sample_every");
    ProgressLine progress(cfg.real("progress_interval"), end, rank == 0);
    auto sample_due = [&](long long s) { return s % every == 0 || s == n_eq || s == end; };
    if (sim.step_index() == n_eq && series.empty()) series.push_back(sim.measure());
    RunGuard guard(cfg, sim);
    sim.reset_phase_times();
    const long long timed_from = std::max(sim.step_index(), n_eq);
    Clock::time_point t0 = Clock::now();
    try {
        while (sim.step_index() < end) {
            if (sim.step_index() == n_eq) {  // the measured phase starts: time it alone
                sim.reset_phase_times();
                t0 = Clock::now();
            }
            const long long s = sim.step_index() + 1;
            const bool checkpoint = checkpoint_every > 0 && s % checkpoint_every == 0;
            sim.step(sample_due(s));
            guard.after_step(sim, checkpoint);  // a checkpoint is only written from a good state
            output.on_step(sim);
            if (sample_due(s)) {
                const ThermoSample t = sim.measure();
                guard.on_sample(sim, t);
                output.on_sample(t);
                if (s >= n_eq) series.push_back(t);
                progress.maybe_print(t, s <= n_eq ? "(equilibration)" : "");
            }
            if (checkpoint)
                io::write_checkpoint(req.output_dir + "/checkpoint.h5", sim, cfg, series,
                                     output.fields());
        }
    } catch (const InstabilityError& e) {
        throw InstabilityError(std::string(e.what()) + "; " +
                               save_last_good(sim, guard.last_good(), cfg, series,
                                              req.output_dir));
    }
    const double wall = decomp::max(comm, seconds_since(t0));
    output.finish(sim);

    BlockAverage temperature, pressure, potential;
    for (std::size_t k = 1; k < series.size(); ++k) {
        temperature.add(series[k].temperature);
        pressure.add(series[k].pressure);
        potential.add(series[k].potential);
    }
    if (series.empty()) series.push_back(sim.measure());
    const long long timed_steps = end - timed_from;
    const PhaseTimes& p = sim.phase_times();
    const long long rss = decomp::sum(comm, peak_rss_bytes_of_rank());
    const double n = static_cast<double>(sim.n_global());
    const Int3 dims = sim.rank_grid_dims();
    std::ostringstream json;
    json << "{\n"
         << "  \"scene\": \"" << cfg.scene() << "\",\n"
         << "  \"N\": " << sim.n_global() << ",\n"
         << "  \"ranks\": " << sim.n_ranks() << ",\n"
         << "  \"grid\": \"" << dims.x << "x" << dims.y << "x" << dims.z << "\",\n"
         << "  \"steps\": " << n_steps << ",\n"
         << "  \"equilibration_steps\": " << n_eq << ",\n"
         << "  \"dt\": " << json_number(sim.dt()) << ",\n"
         << "  \"wall_seconds\": " << json_number(wall) << ",\n"
         << "  \"atom_steps_per_second\": " << json_number(wall > 0 ? n * timed_steps / wall : 0)
         << ",\n"
         << "  \"neighbour_rebuilds\": " << sim.rebuilds() << ",\n"
         << "  \"samples\": " << temperature.count() << ",\n"
         << "  \"mean_temperature\": " << json_number(temperature.mean()) << ",\n"
         << "  \"stderr_temperature\": " << json_number(temperature.standard_error()) << ",\n"
         << "  \"mean_pressure\": " << json_number(pressure.mean()) << ",\n"
         << "  \"stderr_pressure\": " << json_number(pressure.standard_error()) << ",\n"
         << "  \"mean_potential_energy\": " << json_number(potential.mean()) << ",\n"
         << "  \"stderr_potential_energy\": " << json_number(potential.standard_error()) << ",\n"
         << "  \"energy_drift_per_particle\": "
         << json_number(series.back().total - series.front().total) << ",\n"
         << "  \"energy_drift_rate\": " << json_number(drift_rate(series)) << ",\n"
         << "  \"final_momentum\": [" << json_number(series.back().momentum.x) << ", "
         << json_number(series.back().momentum.y) << ", "
         << json_number(series.back().momentum.z) << "],\n"
         << "  \"seconds_neighbour\": " << json_number(decomp::max(comm, p.neighbour)) << ",\n"
         << "  \"seconds_force\": " << json_number(decomp::max(comm, p.force)) << ",\n"
         << "  \"seconds_integrate\": " << json_number(decomp::max(comm, p.integrate)) << ",\n"
         << "  \"seconds_communicate\": " << json_number(decomp::max(comm, p.communicate))
         << ",\n"
         << "  \"peak_rss_bytes\": " << rss << ",\n"
         << "  \"bytes_per_particle\": " << json_number(rss / n) << "\n"
         << "}\n";

    if (rank == 0) {
        if (!req.output_dir.empty()) {
            std::ostringstream table;
            table << "# step time temperature pressure kinetic potential total px py pz\n";
            for (const auto& t : series)
                table << t.step << ' ' << json_number(t.time) << ' ' << json_number(t.temperature)
                      << ' ' << json_number(t.pressure) << ' ' << json_number(t.kinetic) << ' '
                      << json_number(t.potential) << ' ' << json_number(t.total) << ' '
                      << json_number(t.momentum.x) << ' ' << json_number(t.momentum.y) << ' '
                      << json_number(t.momentum.z) << '\n';
            io::write_atomically(req.output_dir + "/thermo.dat", table.str());
            io::write_atomically(req.output_dir + "/summary.json", json.str());
        }
        if (!req.summary_json.empty()) io::write_atomically(req.summary_json, json.str());
    }
    return json.str();
}

}  // namespace emergent::app

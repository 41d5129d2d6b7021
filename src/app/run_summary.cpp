// SPDX-License-Identifier: MIT
// Run summary.
#include "app/run_summary.hpp"

#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <sstream>

#include "decomposition/reductions.hpp"
#include "emergent/execution.hpp"
#include "gpu/device_memory_use.hpp"
#include "emergent/block_average.hpp"
#include "emergent/build_info.hpp"

namespace emergent::app {

namespace {
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

std::string number(double v) {
    if (!std::isfinite(v)) return "null";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.12g", v);
    return buf;
}

/// A JSON string: quotes, backslashes and control characters escaped.
std::string quoted(const std::string& text) {
    std::string out = "\"";
    for (const char c : text) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (static_cast<unsigned char>(c) < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(c));
            out += buf;
        } else {
            out += c;
        }
    }
    return out + "\"";
}

long long peak_rss_bytes_of_rank() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return static_cast<long long>(usage.ru_maxrss) * 1024;  // Linux reports kilobytes
}
}  // namespace

std::string summary_json(const Simulation& sim, const Config& cfg,
                         const std::vector<ThermoSample>& series, double wall,
                         long long timed_steps, const Measures& scene_measures) {
    MPI_Comm comm = sim.comm();
    BlockAverage temperature, pressure, potential;
    for (std::size_t k = 1; k < series.size(); ++k) {
        temperature.add(series[k].temperature);
        pressure.add(series[k].pressure);
        potential.add(series[k].potential);
    }
    const PhaseTimes& p = sim.phase_times();
    const long long rss = decomp::sum(comm, peak_rss_bytes_of_rank());
    const double n = static_cast<double>(sim.n_global());
    const Int3 dims = sim.rank_grid_dims();
    const ThermoSample& first = series.front();
    const ThermoSample& last = series.back();
    std::ostringstream json;
    auto field = [&](const std::string& name, const std::string& value, bool comma = true) {
        json << "  \"" << name << "\": " << value << (comma ? ",\n" : "\n");
    };
    json << "{\n";
    field("scene", "\"" + cfg.scene() + "\"");
    // What was run, so the summary alone says it: every parameter as resolved (defaults,
    // preset, files, --set), and the build.
    std::string parameters = "{";
    for (const auto& [key, value] : cfg.values())
        parameters += (parameters.size() > 1 ? ", " : "") + quoted(key) + ": " + quoted(value);
    field("parameters", parameters + "}");
    field("build", "{\"version\": " + quoted(build::version) + ", \"git_commit\": " +
                       quoted(build::git_commit) + ", \"build_type\": " + quoted(build::build_type) +
                       ", \"compiler\": " + quoted(build::compiler) + ", \"cuda\": " +
                       quoted(build::cuda) + "}");
    field("N", std::to_string(sim.n_global()));
    field("ranks", std::to_string(sim.n_ranks()));
    field("grid", "\"" + std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" +
                      std::to_string(dims.z) + "\"");
    field("steps", std::to_string(cfg.integer("steps")));
    field("equilibration_steps", std::to_string(cfg.integer("equilibration_steps")));
    field("dt", number(sim.dt()));
    field("wall_seconds", number(wall));
    field("atom_steps_per_second", number(wall > 0 ? n * timed_steps / wall : 0));
    field("neighbour_rebuilds", std::to_string(sim.rebuilds()));
    field("samples", std::to_string(temperature.count()));
    field("mean_temperature", number(temperature.mean()));
    field("stderr_temperature", number(temperature.standard_error()));
    field("mean_pressure", number(pressure.mean()));
    field("stderr_pressure", number(pressure.standard_error()));
    field("mean_potential_energy", number(potential.mean()));
    field("stderr_potential_energy", number(potential.standard_error()));
    field("energy_drift_per_particle", number(last.total - first.total));
    field("energy_drift_rate", number(drift_rate(series)));
    field("final_momentum", "[" + number(last.momentum.x) + ", " + number(last.momentum.y) +
                                ", " + number(last.momentum.z) + "]");
    // The phases' times are the host's wall clock. On cuda the loops run asynchronously, so a
    // phase's device time lands where the host next waits for a result (the rebuild test's
    // read-back, mostly): the split is not the device's (EMERGENT_PROFILE=1 gives that).
    field("phase_times", sim.backend() == Backend::Cuda ? "\"host clock, device loops asynchronous\""
                                                        : "\"host clock\"");
    field("seconds_neighbour", number(decomp::max(comm, p.neighbour)));
    field("seconds_force", number(decomp::max(comm, p.force)));
    field("seconds_integrate", number(decomp::max(comm, p.integrate)));
    field("seconds_migrate", number(decomp::max(comm, p.migrate)));
    field("seconds_communicate", number(decomp::max(comm, p.communicate)));
    // Blocked on ghost data (inside communicate, or inside force where the refresh overlaps).
    field("seconds_halo_wait", number(decomp::max(comm, p.halo_wait)));
    // In the step's global reductions (inside communicate and integrate): a rank waits there
    // for the slowest, step by step, which the run-long imbalance below averages away.
    field("seconds_collective_wait", number(decomp::max(comm, p.collective_wait)));
    field("seconds_collective_wait_after_build", number(decomp::max(comm, p.collective_wait_after_build)));
    field("halo_overlap", sim.halo_overlap() ? "true" : "false");
    field("interior_fraction", number(decomp::sum(comm, sim.interior_fraction()) / sim.n_ranks()));
    // Load imbalance: how much longer the slowest rank computed (forces and integration) than
    // the ranks' mean, time the others spend waiting at the next exchange.
    const double compute = p.force + p.integrate;
    field("seconds_imbalance", number(decomp::max(comm, compute) - decomp::sum(comm, compute) / sim.n_ranks()));
    // Work per rank as load balance counts it (list entries + a share per particle), now and
    // before the first and latest rebalance (balance=cost).
    const LoadBalanceStats& balance = sim.load_balance();
    field("cost_imbalance", number(sim.cost_imbalance()));
    field("rebalances", std::to_string(balance.rebalances));
    field("cost_imbalance_first", number(balance.imbalance_first));
    field("cost_imbalance_last", number(balance.imbalance_last));
    // Point-to-point traffic of the measured phase, summed over ranks (Simulation::message_traffic).
    const MessageTraffic traffic = sim.message_traffic();
    auto put_traffic = [&](const char* purpose, const MessageCounts& c) {
        field(std::string("messages_") + purpose, std::to_string(decomp::sum(comm, c.messages)));
        field(std::string("message_bytes_") + purpose, std::to_string(decomp::sum(comm, c.bytes)));
    };
    put_traffic("ghost_refresh", traffic.ghost_refresh);
    put_traffic("ghost_build", traffic.ghost_build);
    put_traffic("migration", traffic.migration);
    if (!scene_measures.empty()) {
        // The scene's own measures at the last sample.
        std::string scene = "{";
        for (std::size_t k = 0; k < scene_measures.size(); ++k) {
            const auto& [name, value] = scene_measures[k];
            scene += (k ? ", \"" : "\"") + name + "\": ";
            if (value.size() == 1) {
                scene += number(value[0]);
            } else {
                scene += "[";
                for (std::size_t j = 0; j < value.size(); ++j) scene += (j ? ", " : "") + number(value[j]);
                scene += "]";
            }
        }
        field("scene_measures", scene + "}");
    }
    // Host<->back-end copies since the start, all ranks (none on the host back end).
    const exec::Transfers& moved = exec::transfers();
    const char* backend = sim.backend() == Backend::Cuda       ? "cuda"
                          : sim.backend() == Backend::Checking ? "checking"
                                                               : "host";
    field("backend", std::string("\"") + backend + "\"");
    auto total = [&](std::uint64_t count) {
        return std::to_string(decomp::sum(comm, static_cast<long long>(count)));
    };
    field("transfers", "{\"arrays\": " + total(moved.arrays) + ", \"array_bytes\": " +
                           total(moved.array_bytes) + ", \"scalars\": " + total(moved.scalars) + "}");
    // The step ledger of the measured phase: the most work one step of each kind took, the
    // largest over the ranks.
    const StepLedger& ledger = sim.step_ledger();
    auto work = [&](const StepWork& w) {
        long long v[5] = {static_cast<long long>(w.passes), static_cast<long long>(w.read_backs),
                          static_cast<long long>(w.collectives), static_cast<long long>(w.arrays),
                          static_cast<long long>(w.array_bytes)};
        MPI_Allreduce(MPI_IN_PLACE, v, 5, MPI_LONG_LONG, MPI_MAX, comm);
        return "{\"passes\": " + std::to_string(v[0]) + ", \"read_backs\": " + std::to_string(v[1]) +
               ", \"collectives\": " + std::to_string(v[2]) + ", \"arrays\": " + std::to_string(v[3]) +
               ", \"array_bytes\": " + std::to_string(v[4]) + "}";
    };
    field("step_ledger", "{\"plain_step\": " + work(ledger.plain_step) +
                             ", \"sampled_step\": " + work(ledger.sampled_step) +
                             ", \"list_build\": " + work(ledger.list_build) +
                             ", \"plain_steps\": " + std::to_string(ledger.plain_steps) +
                             ", \"sampled_steps\": " + std::to_string(ledger.sampled_steps) +
                             ", \"builds\": " + std::to_string(ledger.builds) + "}");
    // Device memory the run holds, all ranks (with one device per rank; ranks sharing one
    // count each other's too).
    if (sim.backend() == Backend::Cuda)
        field("device_bytes_per_particle",
              number(static_cast<double>(decomp::sum(
                         comm, static_cast<long long>(gpu::run_device_bytes()))) / n));
    field("peak_rss_bytes", std::to_string(rss));
    field("bytes_per_particle", number(rss / n), false);
    json << "}\n";
    return json.str();
}

std::string thermo_table(const std::vector<ThermoSample>& series) {
    std::ostringstream table;
    table << "# step time temperature pressure kinetic potential total px py pz\n";
    for (const auto& t : series)
        table << t.step << ' ' << number(t.time) << ' ' << number(t.temperature) << ' '
              << number(t.pressure) << ' ' << number(t.kinetic) << ' ' << number(t.potential)
              << ' ' << number(t.total) << ' ' << number(t.momentum.x) << ' '
              << number(t.momentum.y) << ' ' << number(t.momentum.z) << '\n';
    return table.str();
}

}  // namespace emergent::app

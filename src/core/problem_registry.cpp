// SPDX-License-Identifier: MIT
// Scene registry, engine run parameters and configuration resolution; what scenes share.
#include <cstdio>
#include <stdexcept>

#include "emergent/error.hpp"
#include "emergent/problem.hpp"

namespace emergent {

std::string Problem::progress_note(const Measures& measures) const {
    for (const auto& [name, value] : measures)
        if ((name == "revolutions" || name == "cycles") && !value.empty()) {
            char note[48];
            std::snprintf(note, sizeof note, "%s=%.2f", name.c_str(), value[0]);
            return note;
        }
    return "";
}

ProblemRegistry& ProblemRegistry::instance() {
    static ProblemRegistry registry;
    return registry;
}

bool ProblemRegistry::add(ProblemInfo info) {
    const std::string name = info.name;
    if (!problems_.emplace(name, std::move(info)).second)
        throw std::logic_error("scene '" + name + "' is already registered");
    return true;
}

const ProblemInfo* ProblemRegistry::find(const std::string& name) const {
    const auto it = problems_.find(name);
    return it == problems_.end() ? nullptr : &it->second;
}

std::vector<const ProblemInfo*> ProblemRegistry::all() const {
    std::vector<const ProblemInfo*> list;
    for (const auto& [name, info] : problems_) list.push_back(&info);
    return list;
}

namespace {
/// What a run writes and checks: checkpoints, fields, guards, particle frames.
void add_output_parameters(Schema& s) {
    s.integer("checkpoint_every", 0, 0, 1e12, "steps",
                 "steps between checkpoints DIR/checkpoint.h5 (0: none; needs -o DIR)")
        .integer("fields.interval", 0, 0, 1e12, "steps",
                 "steps averaged into one frame of coarse-grained fields (0: no fields)")
        .integer("fields.sample_every", 10, 1, 1e9, "steps", "steps between field samples")
        .text("fields.grid", "1x1x10",
              "NXxNYxNZ cells of the box-wide Cartesian field grid (scenes may add their own)")
        .integer("guard.every", 100, 0, 1e12, "steps",
                 "steps between state checks (finite values, force bound); 0: only at checkpoints")
        .real("guard.max_force", 1e5, 0, 1e300, "epsilon/sigma",
              "stop when a particle's force exceeds this (0: no bound)")
        .real("guard.max_overlap", 1.0, 0, 1e300, "diameters",
              "granular scenes: stop when a contact's overlap exceeds this many sphere diameters "
              "(a pair's mean diameter), checked at sampling steps (0: no bound)")
        .real("guard.max_energy_drift", 0.1, 0, 1e300, "epsilon",
              "energy-conserving runs only (no thermostat, damping or friction): stop when total "
              "energy per particle drifts further (0: no bound)")
        .integer("output.every", 0, 0, 1e12, "steps",
                 "steps between particle frames in trajectory.h5 (0: first and last frame only)")
        .text("output.elements", "position,velocity,species,id,image,diameter",
              "particle elements written per frame (comma-separated)")
        .real("output.snapshot_seconds", 10, 0, 1e300, "seconds",
              "wall seconds between rewrites of DIR/snapshot.h5, the latest fields and measures "
              "for scripts/watch (0: never)");
}
}  // namespace

Schema run_schema() {
    Schema s;
    s.real("dt", 0.005, 0, 1, "tau", "integration time step", true)
        .real("skin", 0.3, 0, 5, "sigma", "neighbour-list skin beyond the largest cutoff", true)
        .integer("cell_subdivisions", 1, 1, 3, "1",
                 "cells per neighbour-list range (cutoff + skin) along each axis for the list "
                 "search: 2 tests 42 % fewer candidate pairs than 1 but ran 30 % slower for WCA "
                 "and no faster for LJ at cutoff 2.5 (benchmarks/results/host_speed.md)")
        .choice("integrator", "verlet", {"verlet", "omelyan"},
                "time-step splitting: verlet (velocity Verlet, one force evaluation per step) or "
                "omelyan (Omelyan-Mryglod-Folk minimum-error scheme, two evaluations per step, "
                "~10x smaller leading error; see benchmarks/results/work_precision.md for when it pays)")
        .choice("backend", "auto", {"auto", "host", "checking", "cuda"},
                "where the particle data live and the per-particle loops run: host (CPU loops), "
                "cuda (the step's loops as kernels on one CUDA device per rank, chosen by the "
                "rank's index on its node; refused where there is none; checked on an H200 by "
                "benchmarks/gpu_check.sh), checking (the host back end with its data kept "
                "apart from the host copy, which is poisoned between syncs: bitwise host's "
                "results, for tests), auto (cuda where this build has CUDA and a device is "
                "visible, else host)")
        .choice("mpi_direct", "auto", {"auto", "on", "off"},
                "messages between ranks from and into the back end's memory without staging "
                "through host memory: auto (where the MPI library says it reads CUDA device "
                "memory), on (always: a CUDA-aware MPI the query does not report; on the checking "
                "back end its separate memory goes to MPI as device memory would, the path's "
                "test), off (always staged)")
        .choice("neighbour_list", "auto", {"auto", "half", "full"},
                "neighbour-list layout: half (each pair once, the host's fastest), full (each pair "
                "under both members, the device's layout; every force term must have a back-end "
                "form), auto (half on the host back end, full elsewhere where the terms allow)")
        .integer("equilibration_steps", 1000, 0, 1e12, "steps",
                 "steps run first, excluded from averages and timing")
        .integer("steps", 10000, 0, 1e12, "steps", "measured steps (averaged and timed)")
        .integer("sample_every", 100, 1, 1e9, "steps",
                 "steps between samples of energy, temperature and pressure")
        .integer("seed", 12345, 0, 9.2e18, "1", "random seed (initial state, thermostat)")
        .text("grid", "auto", "rank grid as NXxNYxNZ (e.g. 2x1x1); auto minimises the ghost volume")
        .choice("balance", "none", {"none", "cost"},
                "where the planes between rank domains lie: none (equal slabs), cost (moved so that "
                "each slab of ranks holds an equal share of the neighbour-list entries plus 2 per "
                "particle, at the start and every balance.every steps; kept in checkpoints)")
        .integer("balance.every", 1000, 0, 1e12, "steps",
                 "steps between rebalances with balance=cost (0: at the start only)")
        .choice("halo_overlap", "off", {"on", "off", "ordered"},
                "on: the ghosts' refresh is in flight while the pair forces that need no ghost are "
                "computed (host half list, several ranks, no bodies or wedge), with the owned "
                "particles ordered interior first; on 2 ranks of one node it gained nothing "
                "(benchmarks/results/scaling.md): for slower networks; ordered: that order with a "
                "blocking refresh (bit for bit on); off: plain cell order")
        .real("progress_interval", 10, 0, 1e9, "s", "wall seconds between progress lines (0: none)");
    add_output_parameters(s);
    // A continued run keeps its field grid; everything else here is run control.
    s.structural({"fields.grid"})
        .adjustable({"dt", "skin", "cell_subdivisions", "integrator", "backend", "neighbour_list",
                     "equilibration_steps", "steps", "sample_every", "seed", "grid", "balance", "balance.every", "halo_overlap", "mpi_direct",
                     "progress_interval", "checkpoint_every", "fields.interval", "fields.sample_every", "guard.every", "guard.max_force",
                     "guard.max_overlap", "guard.max_energy_drift", "output.every",
                     "output.elements", "output.snapshot_seconds"});
    return s;
}

Config resolve_config(const ProblemInfo& info, const std::string& preset,
                      const std::vector<std::string>& ini_files,
                      const std::vector<std::string>& assignments,
                      const std::map<std::string, std::string>& base) {
    std::map<std::string, std::string> values;
    for (const auto& p : info.schema.params()) values[p.name] = p.default_value;
    auto apply = [&](const std::string& key, const std::string& value, const std::string& from) {
        const ParamSpec* spec = info.schema.find(key);
        if (!spec)
            throw InputError(info.name + ": unknown parameter '" + key + "'" + from +
                             " (see: emergent help " + info.name + ")");
        try {
            spec->validate(info.name, value);
        } catch (const InputError& e) {
            throw InputError(e.what() + from);
        }
        values[key] = value;
    };
    for (const auto& [k, v] : base) apply(k, v, " in the checkpoint");
    if (!preset.empty()) {
        const auto it = info.presets.find(preset);
        if (it == info.presets.end()) {
            std::string known;
            for (const auto& [name, _] : info.presets) known += (known.empty() ? "" : ", ") + name;
            throw InputError(info.name + ": unknown preset '" + preset + "' (presets: " + known +
                             ")");
        }
        for (const auto& [k, v] : it->second) apply(k, v, " in preset " + preset);
    }
    for (const auto& file : ini_files)
        for (const auto& a : read_ini(file)) apply(a.key, a.value, a.origin);
    for (const auto& a : assignments) {
        const auto [k, v] = split_assignment(a);
        apply(k, v, "");
    }
    return Config(info.name, std::move(values));
}

}  // namespace emergent

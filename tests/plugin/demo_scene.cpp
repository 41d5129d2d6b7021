// SPDX-License-Identifier: MIT
// An out-of-tree scene for the plugin test: a small WCA gas, built as a shared library.
#include <cmath>
#include <stdexcept>
#include <string>

#include "emergent/plugin.hpp"
#include "emergent/random.hpp"

// tests/CMakeLists.txt builds this file three times under different names; built by hand as
// docs/plugins.md shows, it is the scene "demo-gas".
#ifndef PLUGIN_SCENE_NAME
#define PLUGIN_SCENE_NAME "demo-gas"
#endif

namespace {

class DemoGas final : public emergent::Problem {
public:
    explicit DemoGas(const emergent::Config& c)
        : n_(static_cast<int>(c.integer("n"))), fault_rank_(static_cast<int>(c.integer("fault_rank"))) {}
    void build(emergent::Simulation& sim) override {
        emergent::Box box;
        box.hi = {8, 8, 8};
        sim.set_box(box);
        sim.set_species_masses({1.0});
        sim.add_force(emergent::make_lennard_jones(1, 1, std::pow(2.0, 1.0 / 6)));
    }
    void place_particles(emergent::Simulation& sim) override {
        for (int i = 0; i < n_; ++i)  // a simple cubic lattice of spacing 1.6 inside the box
            sim.add_particle({0.8 + 1.6 * (i % 5), 0.8 + 1.6 * ((i / 5) % 5), 0.8 + 1.6 * (i / 25)},
                             {0, 0, 0}, 0, i);
        sim.assign_thermal_velocities(1.0, 7);
    }
    // A fault met by one rank alone in the middle of a run (tests/cli/one_rank_fails.sh): the
    // others go on into the next step's collectives.
    emergent::Measures measures(emergent::Simulation& sim) override {
        if (sim.rank() == fault_rank_ && sim.step_index() >= 40)
            throw std::runtime_error("demo-gas: fault on rank " + std::to_string(fault_rank_) + " at step " +
                                     std::to_string(sim.step_index()));
        return {};
    }

private:
    int n_, fault_rank_;
};

emergent::ProblemInfo demo_info() {
    emergent::ProblemInfo info;
    info.name = PLUGIN_SCENE_NAME;
    info.description = "plugin test: a WCA gas from a shared library";
    info.schema = emergent::run_schema();
    info.schema.integer("n", 100, 1, 125, "1", "particles");
    info.schema.integer("fault_rank", -1, -1, 1 << 20, "1", "rank that fails at its first sample from step 40 (-1: none)");
    info.schema.structural({"n"});
    info.presets["tiny"] = {{"steps", "100"}, {"equilibration_steps", "0"}};
    info.factory = [](const emergent::Config& c) { return std::make_unique<DemoGas>(c); };
    return info;
}

}  // namespace

#ifdef PLUGIN_WRONG_ABI
#undef EMERGENT_PLUGIN_ABI
#define EMERGENT_PLUGIN_ABI "emergent-plugin-0"
#endif
EMERGENT_PLUGIN(demo_info)

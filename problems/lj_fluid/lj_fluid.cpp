// SPDX-License-Identifier: MIT
// Scene `lj-fluid`: a Lennard-Jones (WCA by default) fluid in a periodic box, started from an
// fcc lattice; the engine's benchmark and validation workhorse.
#include <cmath>

#include "emergent/problem.hpp"
#include "emergent/random.hpp"
#include "emergent/simulation.hpp"

namespace emergent::problems {

namespace {

class LjFluid final : public Problem {
public:
    explicit LjFluid(const Config& c) : config_(c) {}

    void build(Simulation& sim) override {
        const int cells = static_cast<int>(config_.integer("n_cells"));
        const double density = config_.real("density");
        const double temperature = config_.real("temperature");
        const auto seed = static_cast<std::uint64_t>(config_.integer("seed"));
        const double a = std::cbrt(4.0 / density);  // fcc: 4 particles per cubic cell
        Box box;
        box.hi = {cells * a, cells * a, cells * a};
        sim.set_box(box);
        sim.set_species_masses({1.0});
        const bool generic = config_.text("kernel") == "generic";
        sim.add_force(make_lennard_jones(1.0, 1.0, config_.real("cutoff"), generic));
        if (generic) {
            // Terms a general engine would evaluate even when they do nothing: a zero field
            // and a wall no particle reaches (it still tests every particle).
            sim.add_force(make_uniform_field({0, 0, 0}));
            sim.add_force(make_plane_wall(2, -1e6, +1, GranularPair{1000, 0, 0, 0}));
        }
        if (config_.text("thermostat") == "bussi")
            sim.set_thermostat(
                make_bussi_thermostat(temperature, config_.real("thermostat_tau"), seed + 1));
    }

    ParticleEstimate expected_particles(const Simulation&) const override {
        const double n = double(config_.integer("n_cells"));
        return {4 * n * n * n, "n_cells=" + config_.text("n_cells")};
    }

    void place_particles(Simulation& sim) override {
        const int cells = static_cast<int>(config_.integer("n_cells"));
        const double a = sim.box().length().x / cells;
        const Vec3 basis[4] = {{0.25, 0.25, 0.25}, {0.75, 0.75, 0.25}, {0.75, 0.25, 0.75},
                               {0.25, 0.75, 0.75}};
        std::int64_t id = 0;
        const bool random = config_.text("lattice") == "random";
        if (random) {
            // Uniform random positions (overlaps included): a stress test of the guards.
            const auto seed = static_cast<std::uint64_t>(config_.integer("seed"));
            const Vec3 len = sim.box().length();
            for (; id < 4LL * cells * cells * cells; ++id)
                sim.add_particle({len.x * uniform_open(seed, id, 10), len.y * uniform_open(seed, id, 11),
                                  len.z * uniform_open(seed, id, 12)},
                                 {0, 0, 0}, 0, id);
        }
        for (int z = 0; z < cells && !random; ++z)
            for (int y = 0; y < cells; ++y)
                for (int x = 0; x < cells; ++x)
                    for (const Vec3& b : basis)
                        sim.add_particle(a * Vec3{x + b.x, y + b.y, z + b.z}, {0, 0, 0}, 0, id++);
        sim.assign_thermal_velocities(config_.real("temperature"),
                                      static_cast<std::uint64_t>(config_.integer("seed")));
    }

private:
    Config config_;
};

ProblemInfo lj_fluid_info() {
    ProblemInfo info;
    info.name = "lj-fluid";
    info.description = "Lennard-Jones/WCA fluid in a periodic box (benchmark and validation)";
    info.schema = run_schema();
    info.schema.integer("n_cells", 10, 1, 2000, "1", "fcc cells per box edge; N = 4 n_cells^3")
        .real("density", 0.8, 0, 1.5, "sigma^-3", "number density", true)
        .real("temperature", 1.0, 0, 1e4, "epsilon/k_B",
              "initial temperature, and the thermostat's target", true)
        .choice("thermostat", "bussi", {"none", "bussi"},
                "none: NVE; bussi: canonical velocity rescaling (Bussi et al. 2007)")
        .real("thermostat_tau", 0.5, 0, 1e9, "tau", "thermostat relaxation time", true)
        .choice("lattice", "fcc", {"fcc", "random"},
                "initial positions: fcc lattice, or uniform random (overlapping; for stress tests)")
        .real("cutoff", 1.122462048309373, 0, 10, "sigma",
              "pair cutoff (energy-shifted); 2^(1/6) is WCA", true)
        .choice("kernel", "specialised", {"specialised", "generic"},
                "specialised: unused features compiled out; generic: species table, pair "
                "damping (zero), energy every step, a zero field and an unreached wall, all "
                "evaluated (for benchmarks/specialisation_cost.sh)");
    info.schema.structural({"n_cells", "density", "lattice"})
        .adjustable({"temperature", "thermostat", "thermostat_tau", "cutoff", "kernel"});
    info.presets["tiny"] = {{"n_cells", "4"}, {"equilibration_steps", "200"}, {"steps", "200"},
                            {"sample_every", "20"}};
    info.presets["small"] = {{"n_cells", "10"}, {"equilibration_steps", "2000"},
                             {"steps", "10000"}};
    info.presets["bench"] = {{"n_cells", "20"}, {"thermostat", "none"},
                             {"equilibration_steps", "200"}, {"steps", "2000"},
                             {"sample_every", "1000"}};
    info.factory = [](const Config& c) { return std::make_unique<LjFluid>(c); };
    return info;
}

}  // namespace

EMERGENT_REGISTER_PROBLEM(lj_fluid_info);

}  // namespace emergent::problems

// SPDX-License-Identifier: MIT
// An out-of-tree pair law (docs/plugins.md, "A new pair law"): the soft repulsion of dissipative
// particle dynamics, u(r) = (a/2) r_c (1 - r/r_c)^2 for r < r_c, written as one evaluator and
// made a force term by one line, in a scene of its own: a dense soft fluid held at temperature T.
// Built from the public headers alone, as a plugin (tests/CMakeLists.txt; by hand as
// docs/plugins.md shows). Its pressure is checked against published values
// (tests/plugin/soft_fluid_pressure.py).
#include <cmath>
#include <memory>

#include "emergent/pair_law.hpp"
#include "emergent/plugin.hpp"
#include "emergent/random.hpp"
#include "emergent/thermostat.hpp"

namespace {

// --- the pair law: the evaluator ---
/// |f| = a (1 - r/r_c) along the line of centres, u = (a/2) r_c (1 - r/r_c)^2 (Groot & Warren
/// 1997): soft spheres that may overlap.
struct SoftRepulsion {
    emergent::Real a = 25, r_c = 1, cutoff_sq = 1;
    SoftRepulsion(emergent::Real a_, emergent::Real rc) : a(a_), r_c(rc), cutoff_sq(rc * rc) {}
    /// |f| / r at squared distance r2 (< cutoff_sq).
    EMERGENT_HD emergent::Real force_over_r(emergent::Real r2) const {
        const emergent::Real r = std::sqrt(r2);
        return a * (1 - r / r_c) / r;
    }
    EMERGENT_HD emergent::Real energy(emergent::Real r2) const {
        const emergent::Real x = 1 - std::sqrt(r2) / r_c;
        return emergent::Real(0.5) * a * r_c * x * x;
    }
};
// --- end of the pair law ---

class SoftFluid final : public emergent::Problem {
public:
    explicit SoftFluid(const emergent::Config& c) : config_(c) {}

    void build(emergent::Simulation& sim) override {
        const double edge = config_.real("edge");
        emergent::Box box;
        box.hi = {edge, edge, edge};
        sim.set_box(box);
        sim.set_species_masses({1.0});
        const double a = config_.real("a"), r_c = 1.0;
        // The one line that makes the law a force term.
        sim.add_force(emergent::make_pair_term("soft-repulsion", SoftRepulsion(a, r_c), r_c));
        sim.set_thermostat(emergent::make_bussi_thermostat(config_.real("temperature"), 0.5,
                                                           static_cast<std::uint64_t>(config_.integer("seed")) + 1));
    }

    emergent::ParticleEstimate expected_particles(const emergent::Simulation&) const override {
        return {count(), "edge=" + config_.text("edge") + ", density=" + config_.text("density")};
    }

    void place_particles(emergent::Simulation& sim) override {
        // Uniformly at random: soft spheres start from overlaps a hard core would not survive.
        const auto seed = static_cast<std::uint64_t>(config_.integer("seed"));
        const double edge = config_.real("edge");
        const auto n = static_cast<std::int64_t>(count());
        for (std::int64_t id = 0; id < n; ++id)
            sim.add_particle({edge * emergent::uniform_open(seed, id, 10), edge * emergent::uniform_open(seed, id, 11),
                              edge * emergent::uniform_open(seed, id, 12)},
                             {0, 0, 0}, 0, id);
        sim.assign_thermal_velocities(config_.real("temperature"), seed);
    }

private:
    double count() const { return std::round(config_.real("density") * std::pow(config_.real("edge"), 3)); }
    emergent::Config config_;
};

emergent::ProblemInfo soft_fluid_info() {
    emergent::ProblemInfo info;
    info.name = "soft-fluid";
    info.description = "plugin example: a fluid of soft spheres, its pair law defined in the plugin";
    info.schema = emergent::run_schema();
    info.schema.real("edge", 6, 2, 1000, "r_c", "edge of the periodic cubic box")
        .real("density", 3, 0, 100, "r_c^-3", "number density")
        .real("a", 25, 0, 1e6, "k_B T / r_c", "repulsion strength (force at contact)")
        .real("temperature", 1, 0, 1e4, "k_B T", "temperature of the thermostat (Bussi)", true);
    info.schema.structural({"edge", "density"}).adjustable({"temperature"});
    info.presets["tiny"] = {{"dt", "0.01"}, {"equilibration_steps", "500"}, {"steps", "500"}, {"sample_every", "10"}};
    info.presets["check"] = {{"dt", "0.01"}, {"equilibration_steps", "1000"}, {"steps", "10000"},
                             {"sample_every", "10"}};
    info.factory = [](const emergent::Config& c) { return std::make_unique<SoftFluid>(c); };
    return info;
}

}  // namespace

EMERGENT_PLUGIN(soft_fluid_info)

// SPDX-License-Identifier: MIT
// Scene `granular-bed`: spheres settling onto a floor under gravity in a box periodic in x and
// y; the granular benchmark and validation workhorse (compare LAMMPS `pair_style gran/hooke`).
#include <cmath>

#include "emergent/kit/body_shapes.hpp"
#include "emergent/error.hpp"
#include "emergent/problem.hpp"
#include "emergent/random.hpp"
#include "emergent/simulation.hpp"

namespace emergent::problems {

namespace {

class GranularBed final : public Problem {
public:
    explicit GranularBed(const Config& c) : c_(c) {
        // Each lattice site holds one grain: it must fit there without touching its neighbours
        // (a tetrahedron turned any way reaches arm + diameter/2 from its centre), or the start
        // overlaps and the contacts fling the grains apart.
        const bool bodies = c.text("particles") == "tetrahedra";
        const double reach = c.real("diameter") + (bodies ? 2 * c.real("arm") : 0.0);
        if (c.real("spacing") < reach)
            throw InputError(c.scene() + ": spacing=" + c.text("spacing") + " must be at least " +
                             (bodies ? "2 arm + diameter (" : "diameter (") + std::to_string(reach) +
                             "): the grains on the start lattice would overlap");
    }

    void build(Simulation& sim) override {
        const double a = c_.real("spacing");
        Box box;
        box.hi = {a * c_.integer("nx"), a * c_.integer("ny"), c_.real("height")};
        box.periodic[2] = false;
        // The bed fills the bottom of the box: split it across x and y only, so every rank
        // gets a column of the bed rather than some ranks the empty space above it.
        const bool split[3] = {true, true, false};
        sim.set_box(box, split);
        sim.set_species_masses({c_.real("mass")});
        GranularSettings g;
        g.pairs = {GranularPair{c_.real("k_n"), c_.real("gamma_n"), c_.real("gamma_s"), c_.real("mu")}};
        g.max_diameter = c_.real("diameter");
        g.generic = c_.text("kernel") == "generic";
        sim.add_force(make_granular_contacts(g));
        sim.add_force(make_uniform_field({0, 0, -c_.real("gravity")}));
        if (c_.text("particles") == "tetrahedra") {
            const double d = c_.real("diameter");
            tetrahedron_ = sim.add_body_kind(regular_tetrahedron(c_.real("arm")), {0, 0, 0, 0},
                                             {d, d, d, d});
        }
        // The floor touches with the same law; its damping and friction act on the sphere's
        // whole mass rather than a pair's reduced mass, hence the factor 2 on gamma.
        sim.add_force(make_plane_wall(2, 0.0, +1,
                                      GranularPair{c_.real("k_n"), 2 * c_.real("gamma_n"),
                                                   2 * c_.real("gamma_s"), c_.real("mu")}));
    }

    ParticleEstimate expected_particles(const Simulation&) const override {
        const double sites = double(c_.integer("nx")) * double(c_.integer("ny")) * double(c_.integer("nz"));
        return {sites * (tetrahedron_ < 0 ? 1 : 4), "nx=" + c_.text("nx") + ", ny=" + c_.text("ny") +
                                                        ", nz=" + c_.text("nz")};
    }

    void place_particles(Simulation& sim) override {
        const double a = c_.real("spacing"), d = c_.real("diameter");
        const auto seed = static_cast<std::uint64_t>(c_.integer("seed"));
        const double v = std::sqrt(c_.real("temperature") / c_.real("mass"));
        std::int64_t id = 0;
        for (long z = 0; z < c_.integer("nz"); ++z)
            for (long y = 0; y < c_.integer("ny"); ++y)
                for (long x = 0; x < c_.integer("nx"); ++x, ++id) {
                    const Vec3 at{a * (x + 0.5), a * (y + 0.5), a * (z + 0.5)};
                    const Vec3 vel{v * gaussian(seed, id, 0), v * gaussian(seed, id, 1),
                                   v * gaussian(seed, id, 2)};
                    if (tetrahedron_ < 0) {
                        sim.add_particle(at, vel, 0, id, d);
                        continue;
                    }
                    const Quat q = normalized(Quat{gaussian(seed, id, 3), gaussian(seed, id, 4),
                                                   gaussian(seed, id, 5), gaussian(seed, id, 6)});
                    sim.add_body(tetrahedron_, at, q, vel, {0, 0, 0}, id, 4 * id);
                }
    }

private:
    Config c_;
    int tetrahedron_ = -1;
};

ProblemInfo granular_bed_info() {
    ProblemInfo info;
    info.name = "granular-bed";
    info.description = "spheres settling on a floor under gravity (granular benchmark, validation)";
    info.schema = run_schema();
    info.schema.set_default("dt", "0.001").set_default("equilibration_steps", "15000")
        .set_default("steps", "5000");
    info.schema.integer("nx", 33, 1, 1e5, "1", "spheres per row along x (sc lattice)")
        .integer("ny", 33, 1, 1e5, "1", "spheres per row along y")
        .integer("nz", 18, 1, 1e5, "1", "layers")
        .real("spacing", 1.2, 0, 100, "sigma", "lattice spacing (box edge = n spacing)", true)
        .real("height", 30, 0, 1e6, "sigma", "box height (floor at z = 0)", true)
        .real("diameter", 1.0, 0, 100, "sigma", "sphere diameter", true)
        .real("mass", 0.5235987755982988, 0, 1e6, "m", "sphere mass (pi/6: unit density)", true)
        .real("k_n", 2000, 0, 1e9, "epsilon/sigma^2", "overlap stiffness", true)
        .real("gamma_n", 13.089969389957, 0, 1e9, "m/tau", "normal damping (pairs)")
        .real("gamma_s", 6.5449846949787, 0, 1e9, "m/tau", "sliding friction coefficient (pairs)")
        .real("mu", 0.5, 0, 10, "1", "Coulomb cap of sliding friction")
        .real("gravity", 1.0, 0, 1e6, "sigma/tau^2", "gravitational acceleration (-z)")
        .real("temperature", 0.1, 0, 1e6, "epsilon", "initial velocity spread (m <v^2> / 3)")
        .choice("particles", "spheres", {"spheres", "tetrahedra"},
                "single spheres, or rigid tetrahedra of four spheres (arm length `arm`)")
        .real("arm", 0.6, 0, 100, "sigma", "tetrahedra: distance of each sphere from the centre", true)
        .choice("kernel", "specialised", {"specialised", "generic"},
                "specialised: unused contact features compiled out; generic: all compiled in");
    // Continued runs keep the bed's structure; contact law, gravity and kernel may change.
    info.schema.structural({"nx", "ny", "nz", "spacing", "height", "diameter", "mass", "particles", "arm"})
        .adjustable({"k_n", "gamma_n", "gamma_s", "mu", "gravity", "temperature", "kernel"});
    info.presets["tiny"] = {{"nx", "6"}, {"ny", "6"}, {"nz", "4"}, {"equilibration_steps", "500"},
                            {"steps", "500"}, {"sample_every", "100"}};
    info.presets["tiny-tetrahedra"] = {{"nx", "4"}, {"ny", "4"}, {"nz", "3"}, {"spacing", "2.5"},
                                       {"particles", "tetrahedra"}, {"equilibration_steps", "500"},
                                       {"steps", "500"}, {"sample_every", "100"}};
    info.factory = [](const Config& c) { return std::make_unique<GranularBed>(c); };
    return info;
}

}  // namespace

EMERGENT_REGISTER_PROBLEM(granular_bed_info);

}  // namespace emergent::problems

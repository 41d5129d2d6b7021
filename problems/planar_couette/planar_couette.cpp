// SPDX-License-Identifier: MIT
// Scene `planar-couette`: a WCA fluid sheared between two parallel thermal walls moving in
// opposite directions; measures the shear viscosity from the momentum the walls pass through
// the fluid and the shear rate of the measured flow profile. It is the independent viscosity
// measurement behind the Reynolds and Taylor numbers of the taylor-couette scene.
#include <cmath>

#include "emergent/block_average.hpp"
#include "emergent/error.hpp"
#include "emergent/kit/lattice.hpp"
#include "emergent/problem.hpp"
#include "emergent/simulation.hpp"

namespace emergent::problems {

namespace {

class PlanarCouette final : public Problem {
public:
    explicit PlanarCouette(const Config& c)
        : config_(c), width_(c.real("width")), height_(c.real("height")),
          speed_(c.real("wall_speed")) {}

    void build(Simulation& sim) override {
        sim_ = &sim;
        sim.set_box(wall_bounded_layer(width_, width_, height_));
        sim.set_species_masses({1.0});
        sim.add_force(make_wca());
        const double kT = config_.real("wall_temperature");
        const auto seed = static_cast<std::uint64_t>(config_.integer("seed"));
        WallMotion bottom_motion, top_motion;
        bottom_motion.velocity = {-0.5 * speed_, 0, 0};
        top_motion.velocity = {0.5 * speed_, 0, 0};
        bottom_ = sim.add_boundary(
            make_thermal_wall(WallShape::plane(2, 0.0, +1), kT, seed + 21, bottom_motion));
        top_ = sim.add_boundary(
            make_thermal_wall(WallShape::plane(2, height_, -1), kT, seed + 22, top_motion));
    }

    ParticleEstimate expected_particles(const Simulation&) const override {
        return {config_.real("density") * width_ * width_ * height_,
                "density=" + config_.text("density") + ", width=" + config_.text("width") +
                    ", height=" + config_.text("height")};
    }

    void place_particles(Simulation& sim) override {
        fill_wall_bounded_layer(sim, width_, width_, height_, config_.real("density"));
        const double t0 = config_.real("initial_temperature");
        sim.assign_thermal_velocities(t0 > 0 ? t0 : config_.real("wall_temperature"),
                                      static_cast<std::uint64_t>(config_.integer("seed")));
        // Start from the linear profile the walls impose, to skip most of the start-up.
        ParticleStore& s = sim.particles();
        for (std::size_t i = 0; i < s.n_owned(); ++i)
            s.velocity[i].x += speed_ * (s.position[i].z / height_ - 0.5);
    }

    std::vector<FieldGrid> field_grids(const Simulation&) const override {
        FieldGrid g;
        g.name = "profile";
        g.n = {1, 1, static_cast<int>(config_.integer("slabs"))};
        g.lo = {0, 0, 0};
        g.hi = {width_, width_, height_};
        return {g};
    }

    Measures analyse_fields(const FieldGrid& grid, const FieldFrame& f) override {
        const int n = grid.n.z;
        const double dz = height_ / n;
        // Least-squares line v_x = a + b z through the middle half of the channel, weighted by
        // the samples per slab; the layers next to the walls are structured and slip.
        double sw = 0, sz = 0, sv = 0, szz = 0, szv = 0, density = 0, temperature = 0;
        int middle = 0;
        for (int k = n / 4; k < n - n / 4; ++k) {
            const double z = (k + 0.5) * dz, w = f.count[k], v = f.velocity[3 * k];
            sw += w, sz += w * z, sv += w * v, szz += w * z * z, szv += w * z * v;
            density += f.density[k], temperature += f.temperature[k], ++middle;
        }
        const double rate = (sw * szv - sz * sv) / (sw * szz - sz * sz);
        const double offset = (sv - rate * sz) / sw;
        density /= middle, temperature /= middle;
        // Momentum the walls gave the fluid during this frame's interval.
        const WallExchange top = sim_->global_exchange(*top_), bottom = sim_->global_exchange(*bottom_);
        const double interval = sim_->time() - last_time_;
        const double stress =
            0.5 * ((top.momentum.x - last_top_) - (bottom.momentum.x - last_bottom_)) /
            (width_ * width_ * interval);
        last_top_ = top.momentum.x, last_bottom_ = bottom.momentum.x, last_time_ = sim_->time();
        // Slip: how far the fluid at the wall lags the wall, in units of the gradient.
        const double slip = (0.5 * speed_ - (offset + rate * height_)) / rate;
        if (sim_->time() > sim_->measurement_start() + 1e-9) {
            stress_.add(stress), rate_.add(rate), density_.add(density);
            temperature_.add(temperature), slip_.add(slip);
        }
        return {{"shear_rate", {rate}}, {"shear_stress", {stress}}, {"centre_density", {density}},
                {"centre_temperature", {temperature}}, {"slip_length", {slip}}};
    }

    Measures measures(Simulation&) override {
        if (stress_.samples().size() < 2) return {};
        // eta = <stress> / <rate>; errors of the two block averages combined in quadrature.
        const double s = stress_.mean(), g = rate_.mean(), rho = density_.mean();
        const double eta = s / g;
        const double rel = std::hypot(stress_.standard_error() / s, rate_.standard_error() / g);
        return {{"viscosity", {eta, std::fabs(eta) * rel}},
                {"kinematic_viscosity", {eta / rho, std::fabs(eta / rho) * rel}},
                {"mean_shear_rate", {g, rate_.standard_error()}},
                {"mean_centre_density", {rho, density_.standard_error()}},
                {"mean_centre_temperature", {temperature_.mean(), temperature_.standard_error()}},
                {"mean_slip_length", {slip_.mean(), slip_.standard_error()}}};
    }

    Measures saved_state() const override {
        return {{"stress_samples", stress_.samples()}, {"rate_samples", rate_.samples()},
                {"density_samples", density_.samples()},
                {"temperature_samples", temperature_.samples()},
                {"slip_samples", slip_.samples()},
                {"last_frame", {last_top_, last_bottom_, last_time_}}};
    }

    void restore_state(const std::map<std::string, std::vector<double>>& state) override {
        const std::pair<const char*, BlockAverage*> series[] = {
            {"stress_samples", &stress_}, {"rate_samples", &rate_}, {"density_samples", &density_},
            {"temperature_samples", &temperature_}, {"slip_samples", &slip_}};
        for (const auto& [name, average] : series) {
            const auto it = state.find(name);
            if (it != state.end())
                for (double x : it->second) average->add(x);
        }
        const auto last = state.find("last_frame");
        if (last != state.end() && last->second.size() != 3)
            throw InputError(config_.scene() + ": the checkpoint's scene state 'last_frame' holds " +
                             std::to_string(last->second.size()) + " values, not 3");
        if (last != state.end())
            last_top_ = last->second[0], last_bottom_ = last->second[1], last_time_ = last->second[2];
    }

private:
    Config config_;
    double width_, height_, speed_;
    Simulation* sim_ = nullptr;
    BoundaryRule *bottom_ = nullptr, *top_ = nullptr;
    double last_top_ = 0, last_bottom_ = 0, last_time_ = 0;
    BlockAverage stress_{10}, rate_{10}, density_{10}, temperature_{10}, slip_{10};
};

ProblemInfo planar_couette_info() {
    ProblemInfo info;
    info.name = "planar-couette";
    info.description = "WCA fluid sheared between thermal walls: measures the shear viscosity";
    info.schema = run_schema();
    info.schema
        .real("width", 15.245, 2, 1e4, "sigma",
              "periodic box edge in x and y (15.245: 12 lattice cells at density 0.488)", true)
        .real("height", 20.327, 4, 1e4, "sigma",
              "distance between the walls, z (20.327: 16 lattice cells at density 0.488)", true)
        .real("density", 0.488, 0, 1.2, "sigma^-3",
              "lattice number density at the start (the measured centre density is reported)", true)
        .real("wall_temperature", 1.0, 0, 1e4, "epsilon/k_B", "temperature of both walls", true)
        .real("initial_temperature", 0, 0, 1e4, "epsilon/k_B",
              "temperature of the initial velocities (0: the wall temperature)")
        .real("wall_speed", 3.0, 0, 1e3, "sigma/tau",
              "relative speed of the walls (each moves at half of it, opposite ways)")
        .integer("slabs", 20, 4, 100000, "1", "slabs of the flow profile across the channel");
    // Field frames carry the analysis: every run of this scene needs them.
    info.schema.set_default("fields.interval", "2000").set_default("fields.sample_every", "10");
    info.schema.structural({"width", "height", "density", "slabs"})
        .adjustable({"wall_temperature", "initial_temperature", "wall_speed"});
    info.presets["tiny"] = {{"width", "8"}, {"height", "10"}, {"equilibration_steps", "400"},
                            {"steps", "1600"}, {"sample_every", "400"}, {"fields.interval", "400"},
                            {"slabs", "10"}};
    info.presets["small"] = {{"equilibration_steps", "20000"}, {"steps", "200000"},
                             {"sample_every", "10000"}, {"fields.interval", "5000"}};
    info.factory = [](const Config& c) { return std::make_unique<PlanarCouette>(c); };
    return info;
}

}  // namespace

EMERGENT_REGISTER_PROBLEM(planar_couette_info);

}  // namespace emergent::problems

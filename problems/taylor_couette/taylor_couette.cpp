// SPDX-License-Identifier: MIT
// Scene `taylor-couette`: a WCA fluid in the gap between coaxial cylinders, the inner one
// rotating; thermal non-slip walls, elastic (or periodic) ends, one wedge of the annulus with
// rotational periodic images (paper: a quadrant). Taylor vortices appear above Ta_c.
#include <algorithm>
#include <cmath>
#include <limits>

#include "emergent/kit/couette_stability.hpp"
#include "emergent/error.hpp"
#include "emergent/kit/flow_analysis.hpp"
#include "emergent/kit/lattice.hpp"
#include "emergent/problem.hpp"
#include "emergent/simulation.hpp"

namespace emergent::problems {

namespace {

constexpr double kTwoPi = 6.283185307179586;

class TaylorCouette final : public Problem {
public:
    explicit TaylorCouette(const Config& c)
        : config_(c), r_i_(c.real("r_inner")), r_o_(c.real("r_inner") + c.real("gap")),
          length_(c.real("length")), omega_(c.real("omega")),
          wedge_n_(static_cast<int>(c.integer("wedge"))),
          periodic_ends_(c.text("ends") == "periodic") {
        const double nu = c.real("kinematic_viscosity");
        const double eta = r_i_ / r_o_, d = r_o_ - r_i_;
        reynolds_ = omega_ * r_i_ * d / nu;
        // A slower start (stepped or ramped): the vortex count a run ends with depends on how
        // it reached its Re (benchmarks/results/taylor_couette.md, "How many vortices").
        spin_.omega = omega_;
        spin_.start_until = c.real("spin_up_time");
        spin_.ramp = c.real("spin_up_ramp");
        if (spin_.start_until > 0 || spin_.ramp > 0) {
            if (!(omega_ > 0))
                throw InputError(c.scene() + ": spin_up_time / spin_up_ramp need omega > 0");
            spin_.start_factor = c.real("spin_up_omega") / omega_;
        }
        // Linear stability of the run's Couette flow: where vortices appear, and which of the
        // axial modes the cylinder's length admits grows fastest at the run's Re (the one a
        // run started from noise is most likely to show).
        const CouetteStability stability(eta);
        const CouetteStability::Onset onset = stability.onset();
        const double re_c = c.real("critical_reynolds") > 0 ? c.real("critical_reynolds") : onset.reynolds;
        const CouetteStability::AdmissibleMode fastest =
            stability.fastest_admissible_mode(reynolds_, length_ / d, periodic_ends_);
        linear_stability_ = {re_c, kTwoPi / onset.wavenumber * d, double(fastest.vortices),
                             kTwoPi / fastest.wavenumber * d, fastest.growth_rate * nu / (d * d)};
        const double geometry = 4 * d / (r_o_ + r_i_);
        taylor_ = geometry * reynolds_ * reynolds_;
        taylor_critical_ = geometry * re_c * re_c;
    }

    void build(Simulation& sim) override {
        sim.add_force(make_wca());
        if (wedge_n_ >= 2) {
            // The images of one turn must cover the ghost shell: the wedge must be at least
            // cutoff + skin wide at the inner cylinder (a narrower one needs images of images).
            const double alpha = kTwoPi / wedge_n_, shell = sim.interaction_range();
            const double width = r_i_ * std::sin(std::min(alpha, 0.25 * kTwoPi));
            if (width < shell)
                throw InputError(config_.scene() + ": wedge=" + config_.text("wedge") + " is " +
                                 std::to_string(width) + " wide at r_inner=" + config_.text("r_inner") +
                                 ", narrower than the interaction range cutoff + skin = " +
                                 std::to_string(shell) + ": use a smaller wedge count");
        }
        Box box;
        const double margin = 0.5;  // the box reaches past the walls: particles on a wall are inside
        if (wedge_n_ >= 2) {
            box.wedge.n = wedge_n_;
            // Bounding box of the sector 0 <= theta <= 2 pi / n of radius r_o: the axis, the
            // arc's ends, and its crossings of the x and y axes.
            Vec3 lo{0, 0, 0}, hi{0, 0, 0};
            const double alpha = kTwoPi / wedge_n_;
            for (const double t : {0.0, alpha, 0.25 * kTwoPi, 0.5 * kTwoPi, 0.75 * kTwoPi}) {
                if (t > alpha + 1e-12) continue;
                lo.x = std::min(lo.x, r_o_ * std::cos(t)), hi.x = std::max(hi.x, r_o_ * std::cos(t));
                lo.y = std::min(lo.y, r_o_ * std::sin(t)), hi.y = std::max(hi.y, r_o_ * std::sin(t));
            }
            // A cut face on a box face stays exactly there (x = 0 for the quadrant): the turned
            // images must land outside the domain, in the ghost shell.
            auto pad = [&](double v, double sign) { return std::fabs(v) < 1e-9 ? 0.0 : v + sign * margin; };
            box.lo = {pad(lo.x, -1), pad(lo.y, -1), 0};
            box.hi = {pad(hi.x, +1), pad(hi.y, +1), length_};
        } else {
            box.lo = {-r_o_ - margin, -r_o_ - margin, 0};
            box.hi = {r_o_ + margin, r_o_ + margin, length_};
        }
        box.periodic[0] = box.periodic[1] = false;
        box.periodic[2] = periodic_ends_;
        if (!periodic_ends_) box.lo.z = -margin, box.hi.z = length_ + margin;
        // The wedge's images turn x into y: only the axis is split between ranks.
        const bool split[3] = {false, false, true};
        sim.set_box(box, split);
        sim.set_species_masses({1.0});

        const double kT = config_.real("wall_temperature");
        const auto seed = static_cast<std::uint64_t>(config_.integer("seed"));
        inner_ = sim.add_boundary(
            make_thermal_wall(WallShape::cylinder(2, {0, 0, 0}, r_i_, +1), kT, seed + 31, spin_));
        outer_ = sim.add_boundary(
            make_thermal_wall(WallShape::cylinder(2, {0, 0, 0}, r_o_, -1), kT, seed + 32));
        if (!periodic_ends_) {
            sim.add_boundary(make_specular_wall(WallShape::plane(2, 0.0, +1)));
            sim.add_boundary(make_specular_wall(WallShape::plane(2, length_, -1)));
        }
    }

    void place_particles(Simulation& sim) override {
        const Wedge wedge = sim.box().wedge;
        const double r_min = r_i_ + 0.5, r_max = r_o_ - 0.5;
        auto inside = [&](const Vec3& x) {
            const double r = std::hypot(x.x, x.y);
            return r >= r_min && r <= r_max && (!wedge.active() || wedge.turns_into(x) == 0);
        };
        // N = density x the fluid's volume (the wedge's share of the annulus).
        const double angle = wedge.active() ? wedge.angle() : kTwoPi;
        const double volume = 0.5 * angle * (r_o_ * r_o_ - r_i_ * r_i_) * length_;
        const auto target = static_cast<std::int64_t>(std::llround(config_.real("density") * volume));
        const bool periodic[3] = {false, false, periodic_ends_};
        // The lattice spans the box across the axis: the wedge's bounding box, not the whole
        // annulus's (the count is taken ~50 times while the spacing is fitted).
        const Box& box = sim.box();
        fill_lattice_with_count(sim, {box.lo.x, box.lo.y, 0}, {box.hi.x, box.hi.y, length_}, target,
                                periodic, inside);
        const double t0 = config_.real("initial_temperature");
        sim.assign_thermal_velocities(t0 > 0 ? t0 : config_.real("wall_temperature"),
                                      static_cast<std::uint64_t>(config_.integer("seed")));
        if (config_.text("initial_flow") == "couette") {
            // Circular Couette flow v_theta = A r + B / r for the wall's speed at t = 0, so the
            // run starts where the fluid's own spin-up would end.
            const double eta = r_i_ / r_o_, omega = omega_ * spin_.factor(0);
            const double A = -omega * eta * eta / (1 - eta * eta);
            const double B = omega * r_i_ * r_i_ / (1 - eta * eta);
            ParticleStore& s = sim.particles();
            for (std::size_t i = 0; i < s.n_owned(); ++i) {
                const Vec3& x = s.position[i];
                const double r = std::hypot(x.x, x.y), v = A * r + B / r;
                s.velocity[i] += Vec3{-v * x.y / r, v * x.x / r, 0};
            }
        }
    }

    ParticleEstimate expected_particles(const Simulation& sim) const override {
        const double angle = sim.box().wedge.active() ? sim.box().wedge.angle() : kTwoPi;
        return {config_.real("density") * 0.5 * angle * (r_o_ * r_o_ - r_i_ * r_i_) * length_,
                "density=" + config_.text("density") + ", r_inner=" + config_.text("r_inner") +
                    ", gap=" + config_.text("gap") + ", length=" + config_.text("length")};
    }

    std::vector<FieldGrid> field_grids(const Simulation&) const override {
        FieldGrid g;
        g.name = "flow";
        g.kind = FieldGrid::Kind::Cylindrical;
        g.axis = 2;
        g.lo = {0, 0, 0};
        g.hi = {0, 0, length_};
        g.r_min = r_i_;
        g.r_max = r_o_;
        g.theta_min = 0;
        g.theta_max = wedge_n_ >= 2 ? kTwoPi / wedge_n_ : kTwoPi;
        g.n = {static_cast<int>(config_.integer("flow_cells_r")), 1,
               static_cast<int>(config_.integer("flow_cells_z"))};
        return {g};
    }

    Measures measures(Simulation& sim) override {
        const ThermoSample t = sim.measure();
        const WallExchange in = sim.global_exchange(*inner_), out = sim.global_exchange(*outer_);
        return {{"revolutions", {omega_ * spin_.travelled(sim.time()) / kTwoPi}},
                {"inner_omega", {omega_ * spin_.factor(sim.time())}},
                {"fluid_angular_momentum", {t.angular_momentum.z}},
                {"inner_wall_exchange", {double(in.hits), in.angular_momentum, in.energy}},
                {"outer_wall_exchange", {double(out.hits), out.angular_momentum, out.energy}},
                {"reynolds", {reynolds_}},
                {"taylor", {taylor_}},
                {"taylor_critical", {taylor_critical_}},
                {"taylor_over_critical", {taylor_ / taylor_critical_}},
                {"linear_stability", linear_stability_}};
    }

    Measures analyse_fields(const FieldGrid& grid, const FieldFrame& f) override {
        const int nr = grid.n.x, nz = grid.n.z;
        // Radial flow at mid-gap: the middle radial cell, or the two middle ones.
        const int r0 = (nr - 1) / 2, r1 = nr / 2;
        const double inefficiency = config_.real("velocity_sample_inefficiency");
        std::vector<double> vr(nz), noise(nz);
        for (int k = 0; k < nz; ++k) {
            double sum = 0, samples = 0, t = 0;
            for (int r = r0; r <= r1; ++r) {
                const int c = k * nr + r;  // n_theta = 1
                sum += f.count[c] * f.velocity[3 * c];
                samples += f.count[c];
                t += f.count[c] * f.temperature[c];
            }
            vr[k] = samples > 0 ? sum / samples : 0.0;
            // Standard error of a cell's mean flow: kT/m over the samples, which are correlated
            // in time (their effective number is samples / inefficiency).
            noise[k] = samples > 1 ? std::sqrt(inefficiency * (t / samples) / samples) : 0.0;
        }
        // The model's noise ignores how long a cell's mean flow stays correlated (hydrodynamic
        // modes of the cell's size live for many samples): measured from the change since the
        // last frame, it is ~3x the model's in the small system, so the census uses the
        // measured level (the model's alone counted 4-11 "vortices" in noise below onset).
        double factor = 1;
        if (last_vr_.size() == vr.size())
            factor = noise_factor_from_frames(vr, noise, last_vr_, last_noise_);
        last_vr_ = vr;
        last_noise_ = noise;
        for (double& n : noise) n *= factor;
        const double dz = length_ / nz;
        const RollCensus census = count_rolls(vr, noise, 0.5 * dz, dz);
        const DominantMode mode = dominant_mode(vr, length_, periodic_ends_);
        std::vector<double> centres(nz, std::numeric_limits<double>::quiet_NaN());
        std::copy(census.centres.begin(), census.centres.end(), centres.begin());
        double rms = 0;
        for (double v : vr) rms += v * v;
        return {{"radial_velocity_midgap", vr},
                {"radial_velocity_noise", noise},
                {"radial_velocity_noise_factor", {factor}},
                {"vortex_count", {double(census.count)}},
                {"vortex_centres", centres},
                {"axial_mode", {double(mode.index), mode.wavelength, mode.amplitude}},
                {"radial_velocity_rms", {std::sqrt(rms / nz)}}};
    }

    Measures saved_state() const override {
        return {{"last_radial_velocity", last_vr_}, {"last_radial_velocity_noise", last_noise_}};
    }

    void restore_state(const std::map<std::string, std::vector<double>>& state) override {
        for (auto [name, into] : {std::pair{"last_radial_velocity", &last_vr_},
                                  std::pair{"last_radial_velocity_noise", &last_noise_}}) {
            const auto it = state.find(name);
            if (it != state.end()) *into = it->second;
        }
        // The noise model pairs each bin's v_r with its noise (a damaged checkpoint if not).
        if (last_vr_.size() != last_noise_.size())
            throw InputError(config_.scene() + ": the checkpoint's last_radial_velocity has " +
                             std::to_string(last_vr_.size()) + " bins, its noise " +
                             std::to_string(last_noise_.size()));
    }

private:
    Config config_;
    double r_i_, r_o_, length_, omega_;
    WallMotion spin_;  ///< the inner cylinder's rotation, with its start-up
    int wedge_n_;
    bool periodic_ends_;
    double reynolds_ = 0, taylor_ = 0, taylor_critical_ = 0;
    /// Re_c, critical wavelength, and the fastest-growing admissible mode at the run's Re:
    /// its vortex count, wavelength and growth rate (1/tau).
    std::vector<double> linear_stability_;
    BoundaryRule *inner_ = nullptr, *outer_ = nullptr;
    std::vector<double> last_vr_, last_noise_;  ///< the last frame's mid-gap v_r and model noise
};

ProblemInfo taylor_couette_info() {
    ProblemInfo info;
    info.name = "taylor-couette";
    info.description = "WCA fluid between coaxial cylinders, inner rotating: Taylor vortices";
    info.schema = run_schema();
    info.schema.real("r_inner", 50, 1, 1e5, "sigma", "inner cylinder radius", true)
        .real("gap", 25, 2, 1e5, "sigma", "gap d = r_outer - r_inner", true)
        .real("length", 100, 2, 1e6, "sigma", "cylinder length (axis z)", true)
        .real("omega", 0.1, 0, 10, "1/tau", "angular velocity of the inner cylinder")
        .real("spin_up_time", 0, 0, 1e9, "tau",
              "time the inner cylinder turns at spin_up_omega before going to omega (0: omega "
              "from the start)")
        .real("spin_up_omega", 0, 0, 10, "1/tau", "angular velocity during spin_up_time")
        .real("spin_up_ramp", 0, 0, 1e9, "tau",
              "after spin_up_time, time over which the speed rises linearly to omega (0: a step)")
        .real("density", 0.488, 0, 1.2, "sigma^-3",
              "number density of the initial lattice; 0.488 = the paper's N/V: 1.2e5 atoms in "
              "the quadrant of r_i=50, d=25, L=100 (V = 2.454e5), or 2.35e6 in r_i=100, d=40, "
              "L=640 (V = 4.825e6)", true)
        .real("wall_temperature", 1.0, 0, 1e4, "epsilon/k_B", "temperature of both cylinders", true)
        .real("initial_temperature", 0, 0, 1e4, "epsilon/k_B",
              "temperature of the initial velocities (0: the wall temperature)")
        .integer("wedge", 4, 1, 64, "1",
                 "simulate the wedge 2 pi / n with rotational images (4: the paper's quadrant; "
                 "1: the full annulus)")
        .choice("ends", "reflecting", {"reflecting", "periodic"},
                "cylinder ends: elastic (specular) caps, or periodic along the axis")
        .choice("initial_flow", "couette", {"couette", "rest"},
                "start with the laminar circular Couette profile, or with the fluid at rest")
        .real("kinematic_viscosity", 1.156, 0, 1e6, "sigma^2/tau",
              "nu of the fluid at the run's state, for Re and Ta; 1.156 +- 0.026 is what "
              "planar-couette measures at the small preset's mid-gap state (rho 0.444, T 2.1, "
              "benchmarks/results/taylor_couette.md); measure it anew for other states", true)
        .real("critical_reynolds", 0, 0, 1e6, "1",
              "Re_c for the radius ratio (0: from linear stability, computed for the run's "
              "radius ratio)")
        .integer("flow_cells_r", 10, 1, 100000, "1", "radial cells of the flow grid")
        .integer("flow_cells_z", 40, 1, 1000000, "1", "axial cells of the flow grid")
        .real("velocity_sample_inefficiency", 4, 1, 1e6, "1",
              "samples per independent velocity sample in a field cell: the noise model of the "
              "first frame; later frames measure the noise from the change since the last one",
              true);
    // Skin 0.7: atoms near the inner wall (speed 5) age the list fast; 0.7 is 1.36x faster
    // than the engine's 0.3 in the small system (skin sweep in benchmarks/results/taylor_couette.md).
    info.schema.set_default("fields.interval", "2000").set_default("fields.sample_every", "10")
        .set_default("skin", "0.7");
    // The inner cylinder's speed (smooth thermal wall) may change between segments; the
    // geometry and the flow grid may not.
    info.schema.structural({"r_inner", "gap", "length", "density", "wedge", "ends", "flow_cells_r",
                            "flow_cells_z"})
        .adjustable({"omega", "spin_up_time", "spin_up_omega", "spin_up_ramp", "wall_temperature",
                     "initial_temperature", "initial_flow", "kinematic_viscosity",
                     "critical_reynolds", "velocity_sample_inefficiency"});
    info.presets["tiny"] = {{"r_inner", "10"}, {"gap", "5"}, {"length", "10"}, {"omega", "0.2"},
                            {"equilibration_steps", "0"}, {"steps", "400"},
                            {"sample_every", "100"}, {"fields.interval", "200"},
                            {"flow_cells_r", "5"}, {"flow_cells_z", "5"}};
    // The paper's small system (~1e4 steps per revolution), reached by a stepped start: held
    // at omega 0.07 (Re ~82, where the 4-vortex mode, lambda_c = 2 d, outgrows the 5-vortex
    // one 1.9 : 1.0) until those rolls saturate, then stepped to 0.1 for 350 tau (their
    // amplitude there saturates within ~250 tau). Started at 0.1 at once, 5 vortices (1.6 d,
    // the fastest-growing mode at Re 108) formed in 4 of 6 seeds; stepped, 4 in every seed
    // run (benchmarks/results/taylor_couette.md, "A stepped start"). The sudden start: --set spin_up_time=0
    // --set steps=150000.
    info.presets["small"] = {{"equilibration_steps", "0"}, {"steps", "420000"},
                             {"spin_up_omega", "0.07"}, {"spin_up_time", "1750"},
                             {"sample_every", "1000"}, {"fields.interval", "5000"},
                             {"progress_interval", "30"}};
    info.presets["paper"] = {{"r_inner", "100"}, {"gap", "40"}, {"length", "640"},
                             {"omega", "0.04"}, {"equilibration_steps", "0"},
                             {"steps", "19000000"}, {"sample_every", "10000"},
                             {"fields.interval", "20000"}, {"flow_cells_r", "16"},
                             {"flow_cells_z", "256"}, {"output.every", "1000000"}};
    info.factory = [](const Config& c) { return std::make_unique<TaylorCouette>(c); };
    return info;
}

}  // namespace

EMERGENT_REGISTER_PROBLEM(taylor_couette_info);

}  // namespace emergent::problems

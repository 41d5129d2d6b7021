// SPDX-License-Identifier: MIT
// Scene `rayleigh-benard`: a WCA fluid between a hot bottom and a cold top thermal wall, under
// gravity, periodic in x and y. Above onset, convection cells form; they are found as the
// temperature minima of a horizontal slice at 0.3 of the height (cold fluid sinks at the cell
// centres) and measured by their periodic Voronoi polygons and by the slice's power spectrum.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "emergent/block_average.hpp"
#include "emergent/kit/cell_pattern.hpp"
#include "emergent/error.hpp"
#include "emergent/kit/lattice.hpp"
#include "emergent/kit/planar_noise.hpp"
#include "emergent/problem.hpp"
#include "emergent/simulation.hpp"

namespace emergent::problems {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

class RayleighBenard final : public Problem {
public:
    explicit RayleighBenard(const Config& c)
        : config_(c), lx_(c.real("width_x")), ly_(c.real("width_y")), lz_(c.real("height")),
          t_hot_(c.real("t_hot")), t_cold_(c.real("t_cold")),
          // g = scale x 3 dT / (2 Lz): at scale 1 the potential energy an atom loses falling
          // through the layer equals the kinetic energy 3 dT / 2 it gains from the walls.
          gravity_(c.real("gravity_scale") * 1.5 * (c.real("t_hot") - c.real("t_cold")) / c.real("height")) {
        if (!(t_hot_ > t_cold_) && c.real("gravity_scale") > 0)
            throw InputError(c.scene() + ": t_hot=" + std::to_string(t_hot_) +
                             " must exceed t_cold (heated from below)");
    }

    void build(Simulation& sim) override {
        sim_ = &sim;
        sim.set_box(wall_bounded_layer(lx_, ly_, lz_));
        sim.set_species_masses({1.0});
        sim.add_force(make_wca());
        if (gravity_ > 0) sim.add_force(make_uniform_field({0, 0, -gravity_}));
        const auto seed = static_cast<std::uint64_t>(config_.integer("seed"));
        bottom_ = sim.add_boundary(make_thermal_wall(WallShape::plane(2, 0.0, +1), t_hot_, seed + 41));
        top_ = sim.add_boundary(make_thermal_wall(WallShape::plane(2, lz_, -1), t_cold_, seed + 42));
        const double layer = config_.real("layer_thickness");
        // A period in time, not in steps: the layers' pull towards the wall temperature (and
        // with it the heat flux, ~2 % between periods 0.02 and 0.1) must not change with dt.
        const double period = config_.real("layer_period");
        const long long every = sim.steps_in(period);
        if (layer > 0) {
            bottom_layer_ = sim.add_wall_layer(
                std::make_unique<WallLayerThermostat>(2, -1.0, layer, t_hot_, every));
            top_layer_ = sim.add_wall_layer(
                std::make_unique<WallLayerThermostat>(2, lz_ - layer, lz_ + 1.0, t_cold_, every));
        }
    }

    ParticleEstimate expected_particles(const Simulation&) const override {
        return {config_.real("density") * lx_ * ly_ * lz_,
                "density=" + config_.text("density") + ", width_x=" + config_.text("width_x") +
                    ", width_y=" + config_.text("width_y") + ", height=" + config_.text("height")};
    }

    void place_particles(Simulation& sim) override {
        fill_wall_bounded_layer(sim, lx_, ly_, lz_, config_.real("density"));
        // Start from the conduction profile, T falling linearly from the hot to the cold wall.
        const double mean = 0.5 * (t_hot_ + t_cold_);
        sim.assign_thermal_velocities(mean, static_cast<std::uint64_t>(config_.integer("seed")));
        ParticleStore& s = sim.particles();
        for (std::size_t i = 0; i < s.n_owned(); ++i) {
            const double t = t_hot_ + (t_cold_ - t_hot_) * s.position[i].z / lz_;
            s.velocity[i] = std::sqrt(t / mean) * s.velocity[i];
        }
        // Thermal noise seeds the cells only weakly at their wavelength (~1 % of T after
        // smoothing over a cell in the small preset); a broadband seed shortens the wait
        // without choosing the wavelength for them.
        const double noise = config_.real("noise_amplitude");
        if (noise > 0) {
            const double shortest = config_.real("noise_wavelength") * lz_;
            const std::string item = config_.scene() + ": noise_amplitude=" +
                                     config_.text("noise_amplitude") + " with noise_wavelength=" +
                                     config_.text("noise_wavelength");
            // The longest wave of the plane is its larger width.
            if (shortest > std::max(lx_, ly_))
                throw InputError(item + ": no wave of the " + config_.text("width_x") + " x " +
                                 config_.text("width_y") + " layer is that long");
            try {
                perturb_layer_temperature(
                    sim, PlanarNoise(lx_, ly_, shortest, noise,
                                     static_cast<std::uint64_t>(config_.integer("seed")) + 43),
                    lz_);
            } catch (const InputError& e) {
                throw InputError(item + ": " + e.what());
            }
        }
        fresh_start_ = true;
    }

    std::vector<FieldGrid> field_grids(const Simulation&) const override {
        const double cell = config_.real("slice_cell");
        const double z = config_.real("slice_height") * lz_, half = 0.5 * config_.real("slice_thickness");
        FieldGrid slice;
        slice.name = "slice";
        slice.n = {std::max(4, static_cast<int>(std::lround(lx_ / cell))),
                   std::max(4, static_cast<int>(std::lround(ly_ / cell))), 1};
        slice.lo = {0, 0, z - half};
        slice.hi = {lx_, ly_, z + half};
        FieldGrid profile;
        profile.name = "profile";
        profile.n = {1, 1, static_cast<int>(config_.integer("profile_slabs"))};
        profile.lo = {0, 0, 0};
        profile.hi = {lx_, ly_, lz_};
        return {slice, profile};
    }

    Measures analyse_fields(const FieldGrid& grid, const FieldFrame& f) override {
        return grid.name == "slice" ? analyse_slice(grid, f) : analyse_profile(grid, f);
    }

    Measures measures(Simulation& sim) override {
        Measures m = {{"gravity", {gravity_}},
                      {"bottom_wall_energy", {sim.global_exchange(*bottom_).energy}},
                      {"top_wall_energy", {sim.global_exchange(*top_).energy}}};
        if (bottom_layer_)
            m.push_back({"wall_layer_energy", {bottom_layer_->energy(), top_layer_->energy()}});
        if (flux_.count() >= 2) {
            m.push_back({"mean_heat_flux", {flux_.mean(), flux_.standard_error()}});
            const double reference = config_.real("conduction_flux");
            if (reference > 0)
                m.push_back({"mean_nusselt", {flux_.mean() / reference, flux_.standard_error() / reference}});
        }
        if (cells_.count() >= 1)
            m.push_back({"mean_cell_count", {cells_.mean(), cells_.standard_error()}});
        return m;
    }

    /// The latest frame's Nusselt number (or heat flux, when no conduction flux is set) and
    /// cell count: what a person waiting for the cells watches.
    std::string progress_note(const Measures&) const override {
        if (!std::isfinite(latest_flux_)) return "";
        const double reference = config_.real("conduction_flux");
        char note[64];
        if (reference > 0)
            std::snprintf(note, sizeof note, "Nu=%.3f cells=%d", latest_flux_ / reference, latest_cells_);
        else
            std::snprintf(note, sizeof note, "heat_flux=%.4f cells=%d", latest_flux_, latest_cells_);
        return note;
    }

    Measures saved_state() const override {
        return {{"heat_flux_samples", flux_.samples()},
                {"cell_count_samples", cells_.samples()},
                {"last_frame", {have_last_ ? 1.0 : 0.0, last_bottom_, last_top_, last_time_}}};
    }

    void restore_state(const std::map<std::string, std::vector<double>>& state) override {
        auto get = [&](const char* name) {
            const auto it = state.find(name);
            return it == state.end() ? std::vector<double>{} : it->second;
        };
        for (double x : get("heat_flux_samples")) flux_.add(x);
        for (double x : get("cell_count_samples")) cells_.add(x);
        const std::vector<double> last = get("last_frame");  // none: a checkpoint before it was kept
        if (!last.empty() && last.size() != 4)
            throw InputError(config_.scene() + ": the checkpoint's scene state 'last_frame' holds " +
                             std::to_string(last.size()) + " values, not 4");
        if (last.size() == 4)
            have_last_ = last[0] != 0, last_bottom_ = last[1], last_top_ = last[2], last_time_ = last[3];
    }

private:
    /// Energy given to the fluid through the bottom (hot) and top (cold) walls so far: wall
    /// collisions plus the rescaling of the layers next to them.
    std::pair<double, double> wall_heat() const {
        double bottom = sim_->global_exchange(*bottom_).energy;
        double top = sim_->global_exchange(*top_).energy;
        if (bottom_layer_) bottom += bottom_layer_->energy(), top += top_layer_->energy();
        return {bottom, top};
    }

    Measures analyse_profile(const FieldGrid&, const FieldFrame&) {
        // Heat flux through the layer during this frame's interval, per unit area: what the hot
        // wall put in and the cold wall took out (equal in a steady state), and their mean.
        const auto [bottom, top] = wall_heat();
        const double now = sim_->time();
        double in = kNaN, out = kNaN;
        if (fresh_start_ || have_last_) {
            const double interval = now - last_time_, area = lx_ * ly_;
            in = (bottom - last_bottom_) / (area * interval);
            out = -(top - last_top_) / (area * interval);
        }
        have_last_ = true;
        last_bottom_ = bottom, last_top_ = top, last_time_ = now;
        const double flux = 0.5 * (in + out);
        if (now > sim_->measurement_start() + 1e-9 && std::isfinite(flux)) flux_.add(flux);
        latest_flux_ = flux;
        const double reference = config_.real("conduction_flux");
        Measures m = {{"heat_flux", {in, out, flux}}};
        if (reference > 0) m.push_back({"nusselt", {flux / reference}});
        return m;
    }

    Measures analyse_slice(const FieldGrid& grid, const FieldFrame& f) {
        PeriodicField2D field{grid.n.x, grid.n.y, lx_, ly_, f.temperature};
        // Cells without a temperature (fewer than two particle samples: a short frame or a
        // thin slice) take the mean of the others; one NaN would spread through the smoothing.
        double mean = 0, filled = 0;
        for (double t : field.value)
            if (std::isfinite(t)) mean += t, ++filled;
        mean = filled > 0 ? mean / filled : 0;
        for (double& t : field.value)
            if (!std::isfinite(t)) t = mean;
        const PeriodicField2D smooth = smooth_periodic(field, config_.real("centre_smoothing") * lz_);
        const std::vector<Point2> centres = local_minima(smooth);
        const VoronoiPattern cells = periodic_voronoi(centres, lx_, ly_);
        const PatternSpectrum spectrum = pattern_spectrum(field);
        // Vertical flow through the slice: rms over cells of the mean v_z (organised flow), and
        // the spread of the slice temperature.
        double vz2 = 0, t2 = 0;
        const int n = grid.n_cells();
        for (int k = 0; k < n; ++k) {
            vz2 += f.velocity[3 * k + 2] * f.velocity[3 * k + 2];
            t2 += (field.value[k] - mean) * (field.value[k] - mean);
        }
        const auto max_cells = static_cast<std::size_t>(config_.integer("max_cells"));
        std::vector<double> xy(2 * max_cells, kNaN);
        for (std::size_t k = 0; k < centres.size() && k < max_cells; ++k)
            xy[2 * k] = centres[k][0], xy[2 * k + 1] = centres[k][1];
        if (sim_->time() > sim_->measurement_start() + 1e-9) cells_.add(cells.cells);
        latest_cells_ = cells.cells;
        std::vector<double> histogram(cells.edge_histogram.begin(), cells.edge_histogram.end());
        return {{"cell_count", {double(cells.cells)}},
                {"cell_centres", xy},
                {"cell_edges", {cells.mean_edges, cells.six_sided_fraction}},
                {"cell_edge_histogram", histogram},
                {"cell_inradius", {cells.mean_inradius, cells.mean_radial_range, cells.radial_range_spread}},
                {"wavelength_voronoi", {cells.wavelength()}},
                {"wavelength_spectrum", {spectrum.dominant_wavelength}},
                {"slice_vertical_flow_rms", {std::sqrt(vz2 / n)}},
                {"slice_temperature", {mean, std::sqrt(t2 / n)}}};
    }

    Config config_;
    double lx_, ly_, lz_, t_hot_, t_cold_, gravity_;
    Simulation* sim_ = nullptr;
    BoundaryRule *bottom_ = nullptr, *top_ = nullptr;
    WallLayerThermostat *bottom_layer_ = nullptr, *top_layer_ = nullptr;
    bool fresh_start_ = false, have_last_ = false;
    double last_bottom_ = 0, last_top_ = 0, last_time_ = 0;
    double latest_flux_ = kNaN;  ///< of the latest profile frame (progress line only)
    int latest_cells_ = 0;
    BlockAverage flux_{10}, cells_{10};
};

ProblemInfo rayleigh_benard_info() {
    ProblemInfo info;
    info.name = "rayleigh-benard";
    info.description = "WCA fluid heated from below under gravity: convection cells";
    info.schema = run_schema();
    info.schema
        .real("width_x", 679, 4, 1e5, "sigma", "periodic width along x", true)
        .real("width_y", 679, 4, 1e5, "sigma", "periodic width along y", true)
        .real("height", 54.3, 4, 1e5, "sigma", "distance between the walls (z)", true)
        .real("density", 0.4, 0, 1.2, "sigma^-3",
              "N / V of the fluid; 0.4 = the paper's 1e7 atoms in 679 x 679 x 54.3 (0.3995) and "
              "4.8e6 in 543 x 543 x 40.7 (0.4000)", true)
        .real("t_hot", 8, 0, 1e4, "epsilon/k_B", "bottom wall temperature", true)
        .real("t_cold", 1, 0, 1e4, "epsilon/k_B", "top wall temperature", true)
        .real("gravity_scale", 0.5, 0, 100, "1",
              "g in units of 3 (t_hot - t_cold) / (2 height); the paper uses 0.5")
        .real("layer_thickness", 1.122462, 0, 1e3, "sigma",
              "fluid layer next to each wall rescaled to the wall temperature (0: none); "
              "the paper's ~r_c")
        .real("layer_period", 0.1, 0, 1e6, "tau",
              "time between wall-layer rescalings (rounded to whole steps, at least one)")
        .real("slice_height", 0.3, 0, 1, "height", "height of the analysed slice above the hot wall")
        .real("slice_thickness", 2.0, 0.1, 1e4, "sigma", "thickness of the analysed slice")
        .real("slice_cell", 2.0, 0.1, 1e4, "sigma", "edge of the slice's coarse-graining cells")
        .real("centre_smoothing", 0.15, 0, 10, "height",
              "width of the Gaussian the slice temperature is smoothed with before its minima "
              "(cell centres) are found")
        .real("noise_amplitude", 0, 0, 1, "1",
              "rms of a smooth random relative temperature perturbation, T (1 + noise(x, y) "
              "sin(pi z / height)), added at the start; 0: the fluid starts with thermal noise only")
        .real("noise_wavelength", 0.5, 0.01, 1e3, "height",
              "shortest wavelength in that perturbation (all longer ones that fit the box carry "
              "equal amplitudes, so none is favoured)")
        .integer("profile_slabs", 20, 2, 100000, "1", "horizontal slabs of the T(z), rho(z) profile")
        .integer("max_cells", 512, 1, 1000000, "1", "cell centres written per frame (all are counted)")
        .real("conduction_flux", 0, 0, 1e9, "epsilon/(sigma^2 tau)",
              "heat flux of the conduction state of the same layer, for the Nusselt number (0: not "
              "known; run the same layer in a periodic column as wide as it is high, too narrow "
              "for a cell, to measure it)");
    // Skin 0.8: the hot wall's fastest atoms (T = 8) cross skin/2 = 0.15 in ~3 steps, so at
    // the engine's 0.3 lists are rebuilt every 3 steps; 0.7-0.9 is 1.4x faster (skin sweep in
    // benchmarks/results/rayleigh_benard.md).
    info.schema.set_default("fields.interval", "2000").set_default("fields.sample_every", "10")
        .set_default("skin", "0.8");
    // The slice, profile and cell-record sizes shape the recorded series: structural. The walls'
    // temperatures and gravity drive the layer and may change (hysteresis runs).
    info.schema.structural({"width_x", "width_y", "height", "density", "slice_height", "slice_thickness",
                            "slice_cell", "profile_slabs", "max_cells"})
        .adjustable({"t_hot", "t_cold", "gravity_scale", "layer_thickness", "layer_period",
                     "noise_amplitude", "noise_wavelength", "conduction_flux", "centre_smoothing"});
    info.presets["tiny"] = {{"width_x", "12"}, {"width_y", "12"}, {"height", "10"},
                            {"equilibration_steps", "0"}, {"steps", "400"},
                            {"sample_every", "100"}, {"fields.interval", "200"},
                            {"slice_cell", "3"}, {"profile_slabs", "5"}};
    // Only the gradient beyond the adiabatic one (g / c_p) drives convection in this gas, so
    // the effective Rayleigh number grows like s (1 - 0.6 s) height^2 and peaks near s = 0.8:
    // height is the lever. Height 40 at s = 0.83 is above the paper's smaller system; two
    // critical wavelengths (2 x height) across. On 2 cores (2.8-3.5 s per tau) the Nusselt
    // number passes 1.05 after 625-900 tau (29-52 min) in three seeds and levels off at 1.11
    // with four or five cells of inradius ~1.05-1.08 height. Measured neighbours, height 45 and
    // g scale 1.1, grew their cells no sooner in tau (benchmarks/results/rayleigh_benard.md).
    info.presets["small"] = {{"width_x", "160"}, {"width_y", "160"}, {"height", "40"},
                             {"gravity_scale", "0.83"}, {"equilibration_steps", "0"},
                             // Its 40 x 40 column (no room for a cell): 0.5105 +- 0.0027,
                             // benchmarks/rayleigh_benard_nusselt.sh.
                             {"conduction_flux", "0.5105"},
                             // 2500 tau: 1000 reached only the onset (Nu 1.048, still
                             // rising; logs/phenomena/rayleigh-benard/); the convection has
                             // levelled off by ~1500 (logs/phenomena/rayleigh-benard_seed12345/).
                             {"steps", "500000"}, {"sample_every", "5000"},
                             {"fields.interval", "5000"}, {"fields.grid", "40x40x10"},
                             {"progress_interval", "60"}};
    info.presets["medium"] = {{"width_x", "543"}, {"width_y", "543"}, {"height", "40.7"},
                              {"equilibration_steps", "0"}, {"steps", "13000000"},
                              {"sample_every", "10000"}, {"fields.interval", "50000"},
                              {"slice_cell", "4"}, {"fields.grid", "54x54x8"}, {"output.every", "1000000"}};
    info.presets["paper"] = {{"equilibration_steps", "0"}, {"steps", "10000000"},
                             {"sample_every", "10000"}, {"fields.interval", "50000"},
                             {"slice_cell", "4"}, {"fields.grid", "68x68x8"}, {"output.every", "1000000"}};
    info.factory = [](const Config& c) { return std::make_unique<RayleighBenard>(c); };
    return info;
}

}  // namespace

EMERGENT_REGISTER_PROBLEM(rayleigh_benard_info);

}  // namespace emergent::problems

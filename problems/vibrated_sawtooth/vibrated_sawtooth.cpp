// SPDX-License-Identifier: MIT
// Scene `vibrated-sawtooth`: a layer of spheres (two sizes) on a vertically vibrated base of
// asymmetric sawtooth teeth. The flow the teeth drive is stratified by height; with the
// vibration's vertical size segregation it sorts the sizes horizontally (paper: "Segregation in
// a vibrated layer"; Levanon & Rapaport 2001, Rapaport 2001).
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <utility>
#include <vector>

#include "emergent/boundary.hpp"
#include "emergent/kit/cycle_average.hpp"
#include "emergent/error.hpp"
#include "emergent/kit/lattice.hpp"
#include "emergent/problem.hpp"
#include "emergent/random.hpp"
#include "emergent/kit/segregation.hpp"
#include "emergent/simulation.hpp"

namespace emergent::problems {

namespace {

constexpr double kTwoPi = 6.283185307179586;
constexpr double kRange = 1.122462048309373;  // paper: r_c = 2^(1/6) x mean diameter
constexpr int kSmall = 0, kBig = 1;
constexpr double kPacking = 0.6;  // volume fraction of a settled layer, for `depth`

class VibratedSawtooth final : public Problem {
public:
    explicit VibratedSawtooth(const Config& c) : c_(c) {
        container_ = c.text("container");
        rings_ = container_ == "cylinder";
        period_ = c.real("tooth_period");
        height_ = c.real("tooth_height");
        d_small_ = c.real("d_small");
        d_big_ = c.real("d_big");
        spread_ = c.real("size_spread");
        amplitude_ = c.real("amplitude");
        frequency_ = c.real("frequency");
        big_fraction_ = c.real("big_fraction");
        periodic_ = container_ == "slot" && c.text("slot_ends") == "periodic";
        if (rings_) {
            u_max_ = 0.5 * c.real("diameter");
        } else {
            u_max_ = c.real("length");
            width_ = c.real("width");
        }
        check();
        // Masses follow the nominal volumes (unit mass for the small grain).
        const double ratio = d_big_ / d_small_;
        mass_[kSmall] = 1.0;
        mass_[kBig] = ratio * ratio * ratio;
        const auto bins = static_cast<std::size_t>(c.integer("profile_bins"));
        for (int s = 0; s < 2; ++s) {
            profile_sum_[s].assign(bins, 0.0);
            profile_count_[s].assign(bins, 0.0);
        }
    }

    void build(Simulation& sim) override {
        // Cycle averages count from the measured phase's start.
        for (auto* a : {&flux_, &flux_small_, &flux_big_})
            *a = CycleAverage(1.0 / frequency_, sim.measurement_start());
        draw_grains();
        Box box;
        // The top is open in the paper (out of the grains' reach); here the box ends 20 above
        // the loose start, where a smooth lid catches the few grains thrown up while the layer
        // lands (the settled layer hops a few diameters at most).
        double top = 0;
        for (const Vec3& x : start_) top = std::max(top, x.z);
        top += 20;
        if (rings_) {
            box.lo = {-u_max_ - 1, -u_max_ - 1, -amplitude_ - 2};
            box.hi = {u_max_ + 1, u_max_ + 1, top};
        } else {
            box.lo = {0, 0, -amplitude_ - 2};
            box.hi = {u_max_, width_, top};
        }
        box.periodic[0] = periodic_;
        box.periodic[1] = false;
        box.periodic[2] = false;
        // A layer spread over the floor: split the floor, not the empty space above it.
        const bool split[3] = {true, true, false};
        sim.set_box(box, split);
        sim.set_species_masses({mass_[kSmall], mass_[kBig]});
        const GranularPair contact{c_.real("k_n"), c_.real("gamma_n"), 0, 0};
        GranularSettings g;
        g.n_species = 2;
        g.pairs = {contact, contact, contact, contact};
        g.range_factor = kRange;
        g.max_diameter = d_big_;
        sim.add_force(make_granular_contacts(g));
        sim.add_force(make_uniform_field({0, 0, -c_.real("gravity")}));
        RodBase base;
        base.vertices = profile();
        base.period = period_;
        base.rod_spacing = c_.real("rod_spacing");
        base.rod_diameter = c_.real("rod_diameter");
        base.rings = rings_;
        if (!periodic_) {
            base.u_lo = 0;
            base.u_hi = u_max_;
        }
        base.amplitude = amplitude_;
        base.frequency = frequency_;
        base.backing = c_.text("base_backing") == "smooth";
        sim.add_force(make_rod_base(base, contact, kRange));
        // Smooth vertical walls: overlap and normal damping, no friction; the same for the lid.
        // Each is backed by a hard (specular) wall at its surface, which no grain centre
        // crosses: a landing layer presses hard enough to squeeze a grain through a soft wall.
        const GranularPair wall{c_.real("k_n"), c_.real("wall_gamma_n"), 0, 0};
        auto plane = [&](int axis, double at, int side) {
            sim.add_force(make_plane_wall(axis, at, side, wall, kRange));
            sim.add_boundary(make_specular_wall(WallShape::plane(axis, at, side)));
        };
        plane(2, top - 0.5, -1);
        if (rings_) {
            sim.add_force(make_cylinder_wall(u_max_, wall, kRange));
            sim.add_boundary(make_specular_wall(WallShape::cylinder(2, {0, 0, 0}, u_max_, -1)));
        } else {
            if (!periodic_) {
                plane(0, 0.0, +1);
                plane(0, u_max_, -1);
            }
            plane(1, 0.0, +1);
            plane(1, width_, -1);
        }
    }

    // build() draws every grain's start (the box's top follows from it): asked before it.
    ParticleEstimate particles_from_parameters() const override {
        return {double(particle_count()), c_.integer("particles") > 0
                                              ? "particles=" + c_.text("particles")
                                              : "depth=" + c_.text("depth")};
    }
    ParticleEstimate expected_particles(const Simulation&) const override { return particles_from_parameters(); }

    void place_particles(Simulation& sim) override {
        const auto seed = static_cast<std::uint64_t>(c_.integer("seed"));
        const double v0 = c_.real("initial_speed");
        for (std::size_t k = 0; k < start_.size(); ++k) {
            const Vec3 v{v0 * gaussian(seed, k, 2), v0 * gaussian(seed, k, 3), v0 * gaussian(seed, k, 4)};
            sim.add_particle(start_[k], v, species_[k], static_cast<std::int64_t>(k), diameter_[k]);
        }
    }

    /// In a periodic slot nothing but the rods takes up the layer's momentum along x, and a
    /// flat stretch of rods takes it up slowly: the random kicks of landing leave the settled
    /// layer sliding, and that slide would decay only over hundreds of cycles and read as
    /// flux. The measured phase starts without it (the mass-weighted mean v_x removed).
    void on_equilibrated(Simulation& sim) override {
        if (!periodic_) return;
        ParticleStore& p = sim.particles();
        double local[2] = {0, 0}, all[2];
        for (std::size_t i = 0; i < p.n_owned(); ++i) {
            const double m = mass_[p.species[i] == kBig ? kBig : kSmall];
            local[0] += m * p.velocity[i].x;
            local[1] += m;
        }
        MPI_Allreduce(local, all, 2, MPI_DOUBLE, MPI_SUM, sim.comm());
        if (!(all[1] > 0)) return;
        const double drift = all[0] / all[1];
        for (std::size_t i = 0; i < p.n_owned(); ++i) p.velocity[i].x -= drift;
        removed_drift_ = drift;
    }

    Measures measures(Simulation& sim) override {
        const ParticleStore& p = std::as_const(sim).particles();  // read only: nothing to send back
        const std::size_t n = p.n_owned();
        std::vector<double> u(n);
        std::vector<char> big(n);
        // Sums: v_u of all, small, big; counts of small, big; heights of small, big.
        double local[7] = {0, 0, 0, 0, 0, 0, 0};
        const auto bins = profile_sum_[0].size();
        const double bin_height = c_.real("profile_height") / double(bins);
        std::vector<double> bin_local(4 * bins, 0.0);  // v sums small, big; counts small, big
        for (std::size_t i = 0; i < n; ++i) {
            const Vec3& x = p.position[i];
            const Vec3& v = p.velocity[i];
            const double r = std::hypot(x.x, x.y);
            u[i] = rings_ ? r : x.x;
            const double vu = rings_ ? (r > 0 ? (x.x * v.x + x.y * v.y) / r : 0.0) : v.x;
            const int s = p.species[i] == kBig ? 1 : 0;
            big[i] = s == 1;
            local[0] += vu;
            local[1 + s] += vu;
            local[3 + s] += 1;
            local[5 + s] += x.z;
            // Heights above the base's mean level (the lowest rods at rest are at z = 0).
            const double h = x.z;
            if (h >= 0) {
                const auto b = static_cast<std::size_t>(h / bin_height);
                if (b < bins) {
                    bin_local[s * bins + b] += vu;
                    bin_local[(2 + s) * bins + b] += 1;
                }
            }
        }
        double all[7];
        MPI_Allreduce(local, all, 7, MPI_DOUBLE, MPI_SUM, sim.comm());
        std::vector<double> bin_all(bin_local.size());
        MPI_Allreduce(bin_local.data(), bin_all.data(), int(bin_all.size()), MPI_DOUBLE, MPI_SUM,
                      sim.comm());
        const double n_all = all[3] + all[4];
        const double t = sim.time();
        const bool measuring = sim.step_index() >= c_.integer("equilibration_steps");
        if (measuring && t > last_sample_time_) {
            // The running averages take each sample once (a continued run may see one again).
            last_sample_time_ = t;
            flux_.add(t, n_all > 0 ? all[0] / n_all : 0.0);
            if (all[3] > 0) flux_small_.add(t, all[1] / all[3]);
            if (all[4] > 0) flux_big_.add(t, all[2] / all[4]);
            for (int s = 0; s < 2; ++s)
                for (std::size_t b = 0; b < bins; ++b) {
                    profile_sum_[s][b] += bin_all[s * bins + b];
                    profile_count_[s][b] += bin_all[(2 + s) * bins + b];
                }
        }
        const SplitSegregation split = split_segregation(u, big, sim.comm());
        const MixtureBins along = mixture_bins(u, big, 0.0, u_max_, int(c_.integer("segregation_bins")),
                                               sim.comm());
        Measures m;
        const double g = c_.real("gravity");
        m.push_back({"gamma", {std::pow(kTwoPi * frequency_, 2) * amplitude_ / g}});
        m.push_back({"cycles", {frequency_ * t}});
        m.push_back({"horizontal_velocity", {n_all > 0 ? all[0] / n_all : 0.0}});
        const double flux = flux_.mean(), stderr_flux = flux_.standard_error();
        m.push_back({"horizontal_flux", {flux}});
        m.push_back({"horizontal_flux_stderr", {stderr_flux}});
        m.push_back({"horizontal_flux_cycles", {double(flux_.complete_cycles()), double(flux_.block_cycles())}});
        m.push_back({"horizontal_flux_small", {flux_small_.mean(), flux_small_.standard_error()}});
        m.push_back({"horizontal_flux_big", {flux_big_.mean(), flux_big_.standard_error()}});
        m.push_back({"velocity_profile_small", profile(0)});
        m.push_back({"velocity_profile_big", profile(1)});
        m.push_back({"segregation_index",
                     {split.index, split.random_sd, split.random_sd > 0 ? split.index / split.random_sd : 0.0}});
        m.push_back({"big_fraction_along", along.fraction()});
        const double z_small = all[3] > 0 ? all[5] / all[3] : NAN, z_big = all[4] > 0 ? all[6] / all[4] : NAN;
        m.push_back({"mean_height", {z_small, z_big}});
        m.push_back({"removed_drift", {removed_drift_}});
        m.push_back({"segregation_rule", segregation_rule(split, z_big)});
        return m;
    }

    Measures saved_state() const override {
        Measures s{{"flux", flux_.state()},
                   {"flux_small", flux_small_.state()},
                   {"flux_big", flux_big_.state()},
                   {"last_sample_time", {last_sample_time_}},
                   {"removed_drift", {removed_drift_}}};
        for (int k = 0; k < 2; ++k) {
            s.push_back({"profile_sum_" + std::to_string(k), profile_sum_[k]});
            s.push_back({"profile_count_" + std::to_string(k), profile_count_[k]});
        }
        return s;
    }

    void restore_state(const std::map<std::string, std::vector<double>>& s) override {
        auto take = [&](const std::string& key) -> const std::vector<double>& {
            const auto it = s.find(key);
            if (it == s.end()) throw InputError(c_.scene() + ": the checkpoint lacks the scene state '" + key + "'");
            return it->second;
        };
        if (!flux_.restore(take("flux")) || !flux_small_.restore(take("flux_small")) ||
            !flux_big_.restore(take("flux_big")))
            throw InputError(c_.scene() + ": the checkpoint's flux averages are malformed");
        auto scalar = [&](const std::string& key) {
            const auto& v = take(key);
            if (v.size() != 1)
                throw InputError(c_.scene() + ": the checkpoint's scene state '" + key + "' holds " +
                                 std::to_string(v.size()) + " values, not 1");
            return v[0];
        };
        last_sample_time_ = scalar("last_sample_time");
        removed_drift_ = scalar("removed_drift");
        for (int k = 0; k < 2; ++k) {
            const auto& sum = take("profile_sum_" + std::to_string(k));
            const auto& count = take("profile_count_" + std::to_string(k));
            if (sum.size() != profile_sum_[k].size() || count.size() != profile_sum_[k].size())
                throw InputError(c_.scene() + ": the checkpoint's velocity profile has " +
                                 std::to_string(sum.size()) + " sums and " + std::to_string(count.size()) +
                                 " counts, profile_bins is " + std::to_string(profile_sum_[k].size()));
            for (double n : count)
                if (n < 0)
                    throw InputError(c_.scene() + ": the checkpoint's velocity profile has a negative count");
            profile_sum_[k] = sum;
            profile_count_[k] = count;
        }
    }

    std::string progress_note(const Measures& m) const override {
        std::ostringstream out;
        for (const auto& [name, v] : m) {
            if (name == "cycles") out << "cycles " << std::lround(v[0]);
            if (name == "horizontal_flux" && std::isfinite(v[0])) out << ", flux " << v[0];
            if (name == "segregation_index") out << ", segregation " << v[2] << " sd";
        }
        return out.str();
    }

private:
    /// The tooth profile over one period, u from 0 to the period: `sawtooth` rises along its
    /// gentle edge towards +u and drops at the steep one; `mirrored` is that profile reflected
    /// in space (u -> period - u), not a reversed vibration; `flat` a row of rods at z = 0.
    std::vector<std::pair<double, double>> profile() const {
        const std::string kind = c_.text("base");
        const double g = c_.real("gentle_fraction");
        if (kind == "flat") return {{0.0, 0.0}, {period_, 0.0}};
        if (kind == "mirrored") return {{0.0, 0.0}, {(1 - g) * period_, height_}, {period_, 0.0}};
        return {{0.0, 0.0}, {g * period_, height_}, {period_, 0.0}};
    }

    std::vector<double> profile(int s) const {
        std::vector<double> v(profile_sum_[s].size(), NAN);
        for (std::size_t b = 0; b < v.size(); ++b)
            if (profile_count_[s][b] > 0) v[b] = profile_sum_[s][b] / profile_count_[s][b];
        return v;
    }

    /// The rule that can fail: in a closed container the big grains collect at the end toward
    /// which v(z) at their mean height carries them. Returns {predicted direction of the big
    /// grains (+1: toward larger u), observed direction (sign of the big grains' excess at
    /// large u), 1 if they agree, else 0}; NaN in periodic slots (no ends) or before the
    /// profile has samples there.
    std::vector<double> segregation_rule(const SplitSegregation& split, double z_big) const {
        const std::vector<double> all_nan{NAN, NAN, NAN};
        if (periodic_ || !std::isfinite(z_big)) return all_nan;
        const auto bins = profile_sum_[0].size();
        const double bin_height = c_.real("profile_height") / double(bins);
        const auto b = static_cast<std::size_t>(std::max(0.0, z_big) / bin_height);
        if (b >= bins) return all_nan;
        const double count = profile_count_[0][b] + profile_count_[1][b];
        if (!(count > 0)) return all_nan;
        const double v = (profile_sum_[0][b] + profile_sum_[1][b]) / count;
        const double predicted = v > 0 ? 1.0 : -1.0;
        // The split index is the big fraction in the half at small u minus that at large u.
        const double observed = split.index < 0 ? 1.0 : -1.0;
        return {predicted, observed, predicted == observed ? 1.0 : 0.0};
    }

    long long particle_count() const {
        if (c_.integer("particles") > 0) return c_.integer("particles");
        const double area = rings_ ? 0.25 * kTwoPi * u_max_ * u_max_ : u_max_ * width_;
        const double volume = mean_volume();
        // depth in small-grain diameters of a layer packed at kPacking.
        return std::max<long long>(1, std::llround(kPacking * area * c_.real("depth") * d_small_ / volume));
    }

    /// The region the grains start in, above the teeth at their highest: loose (volume fraction
    /// start_fraction), so that the layer settles a short way rather than falling far.
    void start_region(Vec3& lo, Vec3& hi) const {
        const double clear = 0.5 * kRange * d_big_;
        const double area = rings_ ? 0.25 * kTwoPi * u_max_ * u_max_ : u_max_ * width_;
        const double z0 = height_ + amplitude_ + clear + 0.5;
        const double h = double(particle_count()) * mean_volume() / (c_.real("start_fraction") * area);
        if (rings_) {
            lo = {-u_max_, -u_max_, z0};
            hi = {u_max_, u_max_, z0 + h};
        } else {
            // A periodic slot's start keeps one big grain's reach from its seam (the packing
            // does not wrap around).
            lo = {periodic_ ? 0.0 : clear, clear, z0};
            hi = {u_max_ - (periodic_ ? 2 * clear : clear), width_ - clear, z0 + h};
        }
    }

    /// The loose start; where confinement (a narrow slot) jams the packing before it holds
    /// every grain, a taller region (the same every time for a seed).
    std::vector<Vec3> start_positions(const std::vector<double>& diameter, std::uint64_t seed) const {
        Vec3 lo, hi;
        start_region(lo, hi);
        const double radius = u_max_;
        const bool rings = rings_;
        for (int attempt = 0;; ++attempt) {
            try {
                return random_sequential_packing(
                    lo, hi, diameter, kRange, seed ^ 0x5a5a5a5aULL, [radius, rings](const Vec3& x, double d) {
                        return !rings || std::hypot(x.x, x.y) <= radius - 0.5 * kRange * d;
                    }, 2000);
            } catch (const InputError&) {
                if (attempt == 8) throw;
                hi.z = lo.z + 1.5 * (hi.z - lo.z);
            }
        }
    }

    double mean_volume() const {
        const double s = d_small_ - 0.5 * spread_, b = d_big_ - 0.5 * spread_;
        return kTwoPi / 12 * ((1 - big_fraction_) * s * s * s + big_fraction_ * b * b * b);
    }

    /// Sizes, species and starting places of the grains (the same on every rank, and again
    /// when a run continues: the box's top follows from them).
    void draw_grains() {
        const auto seed = static_cast<std::uint64_t>(c_.integer("seed"));
        const auto n = static_cast<std::size_t>(particle_count());
        diameter_.resize(n);
        species_.resize(n);
        for (std::size_t k = 0; k < n; ++k) {
            const bool big = uniform_open(seed, k, 0) < big_fraction_;
            species_[k] = big ? kBig : kSmall;
            diameter_[k] = (big ? d_big_ : d_small_) - spread_ * uniform_open(seed, k, 1);
        }
        start_ = start_positions(diameter_, seed);
    }

    void check() const {
        const std::string s = c_.scene() + ": ";
        if (!(frequency_ > 0)) throw InputError(s + "frequency=" + c_.text("frequency") + " must be > 0");
        if (d_big_ < d_small_)
            throw InputError(s + "d_big=" + c_.text("d_big") + " is smaller than d_small=" + c_.text("d_small"));
        if (!(spread_ < d_small_))
            throw InputError(s + "size_spread=" + c_.text("size_spread") + " must be below d_small");
        // The rod base's own checks, in this scene's names.
        if (!(period_ >= 2 * c_.real("rod_spacing")))
            throw InputError(s + "tooth_period=" + c_.text("tooth_period") + " must be at least 2 rod_spacing (" +
                             std::to_string(2 * c_.real("rod_spacing")) + "): each flank of a tooth needs its rods");
        if (!(c_.real("rod_spacing") >= 0.25 * c_.real("rod_diameter")))
            throw InputError(s + "rod_spacing=" + c_.text("rod_spacing") + " must be at least 0.25 rod_diameter (" +
                             std::to_string(0.25 * c_.real("rod_diameter")) +
                             "): closer rods merge into a surface touching a grain many times over");
        if (period_ > u_max_)
            throw InputError(s + "tooth_period=" + c_.text("tooth_period") + " does not fit the container (" +
                             (rings_ ? "radius " : "length ") + std::to_string(u_max_) + ")");
        if (periodic_) {
            const double teeth = u_max_ / period_;
            if (std::fabs(teeth - std::round(teeth)) > 1e-6 * teeth)
                throw InputError(s + "a periodic slot holds whole teeth: length=" + c_.text("length") +
                                 " is " + std::to_string(teeth) + " tooth_period");
        }
        if (!rings_ && !(width_ >= d_big_ * kRange))
            throw InputError(s + "width=" + c_.text("width") + " is narrower than a big grain (" +
                             std::to_string(d_big_ * kRange) + ")");
    }

    Config c_;
    std::string container_;
    bool rings_ = false, periodic_ = false;
    double period_, height_, d_small_, d_big_, spread_, amplitude_, frequency_, big_fraction_;
    double u_max_ = 0, width_ = 0;
    double mass_[2] = {1.0, 1.0};  ///< per species, set once
    CycleAverage flux_, flux_small_, flux_big_;
    std::vector<double> profile_sum_[2], profile_count_[2];
    double last_sample_time_ = -1;
    double removed_drift_ = 0;  ///< the mean v_x taken out as the measured phase began
    std::vector<Vec3> start_;
    std::vector<double> diameter_;
    std::vector<int> species_;
};

ProblemInfo vibrated_sawtooth_info() {
    ProblemInfo info;
    info.name = "vibrated-sawtooth";
    info.description = "a granular layer on a vibrated sawtooth base: stratified flow, horizontal size segregation";
    info.schema = run_schema();
    // One vibration cycle (f = 0.4) is 500 steps; 10 samples per cycle for the flux.
    info.schema.set_default("dt", "0.005").set_default("equilibration_steps", "10000")
        .set_default("steps", "1000000").set_default("sample_every", "50");
    info.schema
        .choice("container", "box", {"box", "cylinder", "slot"},
                "box (length x width, straight teeth across x), cylinder (diameter, ring teeth), "
                "or slot (a narrow box: width of a few grains)")
        .real("length", 270, 0, 1e6, "sigma", "box or slot length along x (the teeth's axis of asymmetry)", true)
        .real("width", 135, 0, 1e6, "sigma", "box or slot width along y (the teeth run along y)", true)
        .real("diameter", 270, 0, 1e6, "sigma", "cylinder diameter", true)
        .choice("slot_ends", "walls", {"walls", "periodic"},
                "slot: closed by walls (segregation) or periodic along x (net flux)")
        .choice("base", "sawtooth", {"sawtooth", "mirrored", "flat"},
                "sawtooth (gentle edge rising toward +x, or outward in a cylinder), mirrored "
                "(the same teeth reflected in space), flat (one row of rods)")
        .real("tooth_period", 13.5, 0, 1e5, "sigma",
              "tooth period along x (r); 13.5 puts 20 teeth in the 270 box, and with the default "
              "height and vertical steep edge the gentle edge is 13.8 long (paper: about 13)", true)
        .real("tooth_height", 3, 0, 1e5, "sigma",
              "tooth height; 3 (two big grains) is this code's choice (the paper gives the edge "
              "lengths only): a 13 degree gentle slope and a steep edge tall enough to hold grains, "
              "see the flux map in benchmarks/results/vibrated_sawtooth.md", true)
        .real("gentle_fraction", 1.0, 0.5, 1, "1",
              "share of the period taken by the gentle edge: 0.5 symmetric teeth, 1 a vertical "
              "steep edge (the paper's)")
        .real("rod_spacing", 0.5, 0, 10, "sigma", "spacing of the rods along the tooth profile", true)
        .choice("base_backing", "none", {"none", "smooth"},
                "none: the rods alone (the paper's base; a thick or strongly shaken layer can "
                "squeeze a grain between them: benchmarks/results/vibrated_sawtooth.md, flux map); smooth: a surface "
                "along the profile behind the rods, met only by a grain pressed deeper than the "
                "rods let it go")
        .real("rod_diameter", 0.2, 0, 10, "sigma", "diameter of the rods", true)
        .real("frequency", 0.4, 0, 100, "1/tau", "vibration frequency f", true)
        .real("amplitude", 1, 0, 1e3, "sigma", "vibration amplitude a: z_base = a sin(2 pi f t)")
        .real("gravity", 5, 0, 1e6, "sigma/tau^2", "gravitational acceleration (-z)")
        .integer("particles", 0, 0, 1e9, "1", "number of grains (0: from depth)")
        .real("depth", 8.3, 0, 1e4, "sigma",
              "layer depth in small-grain diameters at packing 0.6, used when particles=0 "
              "(8.3 gives the paper's 2e5 grains in the 270 x 135 box)", true)
        .real("big_fraction", 0.3, 0, 1, "1", "fraction of big grains (0: a monodisperse layer)")
        .real("d_small", 1, 0, 100, "sigma", "small grain diameter (before the random reduction)", true)
        .real("d_big", 1.5, 0, 100, "sigma", "big grain diameter (before the random reduction)", true)
        .real("size_spread", 0.1, 0, 100, "sigma", "each diameter is reduced by a uniform random amount below this")
        .real("k_n", 1000, 0, 1e9, "epsilon/sigma^2", "overlap stiffness (grains, rods, walls)", true)
        .real("gamma_n", 5, 0, 1e9, "m/tau", "normal damping between grains and with the rods")
        .real("wall_gamma_n", 5, 0, 1e9, "m/tau", "normal damping of the smooth container walls")
        // At 0.01 and below the start region is over 25 times the settled layer's height: grains fall
        // far enough to hit the base at speeds the contact step does not resolve, and at 1e-300
        // the region's height loses every grain's position to round-off.
        .real("start_fraction", 0.25, 0.01, 0.35, "1",
              "volume fraction of the loose random packing the grains start in, above the teeth", true)
        .real("initial_speed", 0.1, 0, 100, "sigma/tau", "spread of the initial random velocities")
        .integer("profile_bins", 24, 1, 1e5, "1", "height bins of the velocity profiles v(z)")
        .real("profile_height", 24, 0, 1e6, "sigma", "height the velocity profiles span above the base", true)
        .integer("segregation_bins", 27, 1, 1e6, "1", "bins along x (r) of the big-grain fraction");
    info.schema.structural({"container", "length", "width", "diameter", "slot_ends", "base",
                            "tooth_period", "tooth_height", "gentle_fraction", "rod_spacing", "base_backing",
                            "rod_diameter", "frequency", "particles", "depth", "big_fraction",
                            "d_small", "d_big", "start_fraction", "profile_bins",
                            "profile_height", "segregation_bins"})
        .adjustable({"amplitude", "gravity", "size_spread", "k_n", "gamma_n", "wall_gamma_n",
                     "initial_speed"});
    // CI: a periodic slot of two teeth, 6 wide, 4 grains deep (~870 grains), 100 cycles. A
    // monodisperse layer there drifts toward +x (the flow above the base wins; thinner layers
    // drift the other way: benchmarks/results/vibrated_sawtooth.md). A slot 3 wide holds the layer in two rows,
    // whose packing can lock into a tilted order that drives a lasting drift even on a flat
    // base: 6 is wide enough not to.
    info.presets["tiny"] = {{"container", "slot"}, {"slot_ends", "periodic"}, {"length", "27"},
                            {"width", "6"}, {"depth", "4"}, {"equilibration_steps", "5000"},
                            {"steps", "50000"}, {"profile_height", "12"}, {"profile_bins", "12"},
                            {"segregation_bins", "4"}};
    // A closed slot of four teeth, 6 wide, as deep as the paper's layer (~2000 grains, 3000
    // cycles: about 5 minutes on 2 ranks here).
    info.presets["small"] = {{"container", "slot"}, {"slot_ends", "walls"}, {"length", "54"},
                             {"width", "6"}, {"depth", "8.3"}, {"steps", "1500000"},
                             {"sample_every", "250"}, {"output.every", "50000"},
                             {"segregation_bins", "12"}, {"progress_interval", "60"}};
    // The paper's containers. Their 2.3e5 grains landing from the loose start squeeze a grain
    // through the rods alone within 1000 steps (benchmarks/results/vibrated_sawtooth.md): these presets back the
    // rods with the smooth surface.
    info.presets["box"] = {{"container", "box"}, {"base_backing", "smooth"}, {"steps", "1000000"}, {"sample_every", "500"},
                           {"output.every", "100000"}, {"checkpoint_every", "100000"},
                           {"progress_interval", "300"}};
    info.presets["cylinder"] = {{"container", "cylinder"}, {"base_backing", "smooth"}, {"depth", "8.3"}, {"steps", "1000000"},
                                {"sample_every", "500"}, {"output.every", "100000"},
                                {"checkpoint_every", "100000"}, {"progress_interval", "300"}};
    info.factory = [](const Config& c) { return std::make_unique<VibratedSawtooth>(c); };
    return info;
}

}  // namespace

EMERGENT_REGISTER_PROBLEM(vibrated_sawtooth_info);

}  // namespace emergent::problems

// SPDX-License-Identifier: MIT
// Scene `rotating-drum`: a binary mixture of rigid tetrahedra (four spheres each, two arm
// lengths) in a horizontal cylinder turning about its axis, whose curved wall is made rough
// by embedded spheres; radial (small-particle core) and axial (bands) segregation emerge.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "emergent/kit/body_shapes.hpp"
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
constexpr int kSmall = 0, kBig = 1;           // body kinds, and the species of their spheres

/// Smallest sphere-sphere distance between two identically oriented tetrahedra of arm `arm`
/// whose centres are one lattice vector of a simple cubic lattice of spacing `a` apart.
double closest_on_lattice(double arm, double a) {
    const std::vector<Vec3> s = regular_tetrahedron(arm);
    double best = 1e300;
    for (int i = -1; i <= 1; ++i)
        for (int j = -1; j <= 1; ++j)
            for (int k = -1; k <= 1; ++k) {
                if (i == 0 && j == 0 && k == 0) continue;
                const Vec3 shift{a * i, a * j, a * k};
                for (const Vec3& p : s)
                    for (const Vec3& q : s) {
                        const Vec3 d = p - (q + shift);
                        best = std::min(best, std::sqrt(dot(d, d)));
                    }
            }
    return best;
}

/// Central angle alpha of a circular segment whose centroid lies `c` (in units of the radius)
/// from the circle's centre: c = 4 sin^3(alpha/2) / (3 (alpha - sin alpha)), which falls from
/// 1 (alpha -> 0) to 0 (alpha = 2 pi); solved by bisection.
double segment_angle(double c) {
    double lo = 1e-6, hi = kTwoPi;
    for (int k = 0; k < 100; ++k) {
        const double mid = 0.5 * (lo + hi), s = std::sin(0.5 * mid);
        const double cm = 4 * s * s * s / (3 * (mid - std::sin(mid)));
        (cm > c ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

class RotatingDrum final : public Problem {
public:
    explicit RotatingDrum(const Config& c)
        : c_(c), radius_(0.5 * c.real("diameter")), length_(c.real("length")),
          omega_(c.real("omega")), d_(c.real("sphere_diameter")) {
        // Clearance of a body's centre from the walls at the start: its arm plus the contact
        // range with a wall sphere.
        clearance_ = c.real("arm_big") + 0.5 * kRange * (d_ + c.real("wall_sphere_diameter"));
        if (radius_ <= clearance_ + 1 || length_ <= 2 * clearance_ + 1)
            throw InputError(c.scene() + ": diameter=" + std::to_string(2 * radius_) + " and length=" +
                             std::to_string(length_) + " leave no room for a body of arm_big=" +
                             std::to_string(c.real("arm_big")));
        if (c.real("arm_small") > c.real("arm_big"))
            throw InputError(c.scene() + ": arm_small=" + std::to_string(c.real("arm_small")) +
                             " must not exceed arm_big=" + std::to_string(c.real("arm_big")));
        // The wall's own check says the same in its terms; here in the scene's.
        if (!(c.real("wall_spacing") >= 0.25 * c.real("wall_sphere_diameter")))
            throw InputError(c.scene() + ": wall_spacing=" + c.text("wall_spacing") +
                             " must be at least 0.25 wall_sphere_diameter (" +
                             std::to_string(0.25 * c.real("wall_sphere_diameter")) +
                             "): closer wall spheres overlap into a wall that touches a sphere many times over");
    }

    void build(Simulation& sim) override {
        const double margin = 2.0;  // the box reaches past the walls: a sphere on a wall is inside
        Box box;
        box.lo = {-radius_ - margin, -radius_ - margin, -margin};
        box.hi = {radius_ + margin, radius_ + margin, length_ + margin};
        box.periodic[0] = box.periodic[1] = box.periodic[2] = false;
        // The bed lies in the lower part of every cross-section: with equal slabs only the
        // axis is split, so every rank gets a slice of the bed. With balance=cost the planes
        // follow the bed, and where slices of the axis alone would be thinner than about two
        // ghost shells (4 body sizes), x is split too (across the bed, the tilted surface's
        // left from its right; measured slower than axial slices where those suffice,
        // benchmarks/results/scaling.md). Never y as well: planes shared by a whole axis cannot cut a
        // tilted bed into four equal quadrants.
        int ranks = 1;
        MPI_Comm_size(sim.comm(), &ranks);
        const bool across = c_.text("balance") == "cost" && length_ / ranks < 4 * (c_.real("arm_big") + d_);
        const bool split[3] = {across, false, true};
        sim.set_box(box, split);
        sim.set_species_masses({c_.real("sphere_mass"), c_.real("sphere_mass")});

        // Friction: gamma_s by the bodies the spheres belong to; mu proportional to gamma_s,
        // reaching mu_max at the largest gamma_s (paper: 10 -> 0.5, 2 -> 0.1).
        const double gs_small = c_.real("gamma_s_small"), gs_big = c_.real("gamma_s_big"),
                     gs_mixed = c_.real("gamma_s_mixed"), gs_wall = c_.real("gamma_s_wall");
        const double gs_max = std::max({gs_small, gs_big, gs_mixed, gs_wall});
        auto contact = [&](double gamma_n, double gamma_s) {
            return GranularPair{c_.real("k_n"), gamma_n, gamma_s,
                                gs_max > 0 ? c_.real("mu_max") * gamma_s / gs_max : 0.0};
        };
        const double gn = c_.real("gamma_n");
        GranularSettings g;
        g.n_species = 2;
        g.pairs = {contact(gn, gs_small), contact(gn, gs_mixed), contact(gn, gs_mixed),
                   contact(gn, gs_big)};
        g.range_factor = kRange;
        g.max_diameter = d_;
        sim.add_force(make_granular_contacts(g));
        sim.add_force(make_uniform_field({0, -c_.real("gravity"), 0}));

        wall_.radius = radius_;
        wall_.z_lo = 0;
        wall_.z_hi = length_;
        wall_.omega = omega_;
        wall_.spacing = c_.real("wall_spacing");
        wall_.sphere_diameter = c_.real("wall_sphere_diameter");
        sim.add_force(make_rough_cylinder_wall(wall_, contact(gn, gs_wall), kRange));
        // End caps: overlap repulsion and normal damping only (smooth); optionally made rough
        // by spheres embedded in them, turning with the drum and touching like the curved wall.
        const GranularPair cap = contact(c_.real("cap_gamma_n"), 0);
        sim.add_force(make_plane_wall(2, 0.0, +1, cap, kRange));
        sim.add_force(make_plane_wall(2, length_, -1, cap, kRange));
        if (c_.text("end_caps") == "rough")
            for (const double z : {0.0, length_}) {
                RoughEndCap rough;
                rough.z = z;
                rough.radius = radius_ - 0.5 * wall_.spacing;
                rough.omega = omega_;
                rough.spacing = wall_.spacing;
                rough.sphere_diameter = wall_.sphere_diameter;
                sim.add_force(make_rough_end_cap(rough, contact(gn, gs_wall), kRange));
            }

        const std::vector<double> d4(4, d_);
        small_ = sim.add_body_kind(regular_tetrahedron(c_.real("arm_small")), std::vector<int>(4, kSmall), d4);
        big_ = sim.add_body_kind(regular_tetrahedron(c_.real("arm_big")), std::vector<int>(4, kBig), d4);
    }

    void place_particles(Simulation& sim) override {
        // Body centres on a simple cubic lattice filling the drum (all bodies oriented alike,
        // which lets big tetrahedra sit closer than their size); the count sets the fill.
        // An aligned tetrahedron's spheres lie within a sqrt(2) of its axis-parallel line and
        // a along z (a = arm / sqrt(3)); add the contact range with a wall sphere.
        const double a_big = c_.real("arm_big") / std::sqrt(3.0);
        const double contact = 0.5 * kRange * (d_ + c_.real("wall_sphere_diameter"));
        const double r_max = radius_ - (std::sqrt(2.0) * a_big + contact);
        const double z_min = a_big + contact, z_max = length_ - z_min;
        auto inside = [&](const Vec3& x) {
            return x.x * x.x + x.y * x.y <= r_max * r_max && x.z >= z_min && x.z <= z_max;
        };
        const Vec3 lo{-r_max, -r_max, z_min}, hi{r_max, r_max, z_max};
        const bool periodic[3] = {false, false, false};
        const std::int64_t target = body_count();
        const Vec3 a = spacing_for_count(lo, hi, target, periodic, inside);
        // Neighbours may start inside each other's contact range (2^(1/6) d) but not closer
        // than a diameter: at most 0.12 d of overlap, an elastic energy of ~7 per contact, small
        // next to the fall onto the bed (m g h ~ 4 x 5 x D/2 per body). The paper's short drum
        // needs this: 1.36e5 bodies in it leave a lattice spacing of ~2.17.
        const double need = d_;
        if (closest_on_lattice(c_.real("arm_big"), a.x) < need)
            throw InputError(c_.scene() + ": " + std::to_string(target) +
                             " bodies need a lattice spacing of " + std::to_string(a.x) +
                             ", too dense for tetrahedra of arm_big=" +
                             std::to_string(c_.real("arm_big")) + "; lower fill or bodies");
        const std::vector<Vec3> points = cubic_lattice_points(lo, hi, a, inside);
        const auto seed = static_cast<std::uint64_t>(c_.integer("seed"));
        const double v0 = c_.real("initial_speed"), big_fraction = c_.real("big_fraction");
        const Quat aligned{1, 0, 0, 0};
        for (std::size_t k = 0; k < points.size(); ++k) {
            const auto id = static_cast<std::int64_t>(k);
            const int kind = uniform_open(seed, id, 0) < big_fraction ? big_ : small_;
            const Vec3 v{v0 * gaussian(seed, id, 1), v0 * gaussian(seed, id, 2), v0 * gaussian(seed, id, 3)};
            const Vec3 w{v0 * gaussian(seed, id, 4), v0 * gaussian(seed, id, 5), v0 * gaussian(seed, id, 6)};
            sim.add_body(kind, points[k], aligned, v, w, id, 4 * id);
        }
    }

    ParticleEstimate expected_particles(const Simulation&) const override {
        const std::string by = c_.integer("bodies") > 0
                                   ? "bodies=" + c_.text("bodies")
                                   : "fill=" + c_.text("fill") + ", diameter=" + c_.text("diameter") +
                                         ", length=" + c_.text("length");
        return {4.0 * double(body_count()), by};
    }

    Measures measures(Simulation& sim) override {
        const ParticleStore& b = std::as_const(sim).bodies();  // read only: nothing to send back
        const std::size_t n = b.n_owned();
        std::vector<double> z(n), r(n);
        std::vector<char> big(n);
        double sums[3] = {0, 0, 0};  // x, y of the bed's centroid, count
        for (std::size_t i = 0; i < n; ++i) {
            const Vec3& x = b.position[i];
            z[i] = x.z;
            r[i] = std::hypot(x.x, x.y);
            big[i] = b.species[i] == big_;
            sums[0] += x.x, sums[1] += x.y, sums[2] += 1;
        }
        double total[3];
        MPI_Allreduce(sums, total, 3, MPI_DOUBLE, MPI_SUM, sim.comm());
        const double cx = total[2] > 0 ? total[0] / total[2] : 0, cy = total[2] > 0 ? total[1] / total[2] : 0;
        // The small-particle core forms about the centre of the bed's circulation, with big
        // particles both along the wall and along the free surface: the core index splits
        // the bed by distance from its cross-section's centroid. It leaves out the layer next
        // to the curved wall, where big bodies' centres cannot come as close as small ones'
        // (a geometric bias, not segregation).
        const double interior = radius_ - 2 * clearance_;
        std::vector<double> depth;
        std::vector<char> small_interior, big_interior;
        for (std::size_t i = 0; i < n; ++i)
            if (r[i] < interior) {
                depth.push_back(std::hypot(b.position[i].x - cx, b.position[i].y - cy));
                small_interior.push_back(!big[i]);
                big_interior.push_back(big[i]);
            }
        const MixtureBins axial = mixture_bins(z, big, 0, length_, int(c_.integer("axial_slices")), sim.comm());
        const MixtureBins radial = mixture_bins(r, big, 0, radius_, int(c_.integer("radial_shells")), sim.comm());
        const MixtureBins about_centre = mixture_bins(depth, big_interior, 0, radius_,
                                                      int(c_.integer("radial_shells")), sim.comm());
        const SplitSegregation core = split_segregation(depth, small_interior, sim.comm());
        // Bands are counted away from the caps, where big centres cannot come as close as
        // small ones (the end slices are small-rich by geometry alone).
        const double end = length_ > 4 * clearance_ + 1 ? 2 * clearance_ : 0.0;
        const int interior_slices = std::max(
            1, int(std::lround(c_.integer("axial_slices") * (length_ - 2 * end) / length_)));
        const BandCensus bands =
            band_census(mixture_bins(z, big, end, length_ - end, interior_slices, sim.comm()));
        // The bed's cross-section is a circular segment (flat free surface): its centroid lies
        // on the normal to the surface through the axis, so the centroid's direction gives the
        // surface's tilt (the dynamic angle of repose) and its distance the filled fraction.
        const double sense = omega_ < 0 ? -1.0 : 1.0;
        const double repose = std::atan2(sense * cx, -cy) * 360 / kTwoPi;
        const double reach = radius_ - 0.5 * kRange * (d_ + wall_.sphere_diameter);  // centres' circle
        const double alpha = segment_angle(std::min(1.0, std::hypot(cx, cy) / reach));
        return {{"revolutions", {std::fabs(omega_) * sim.time() / kTwoPi}},
                {"froude", {2 * radius_ * omega_ * omega_ / (2 * c_.real("gravity"))}},
                {"big_fraction_axial", axial.fraction()},
                {"bodies_axial", axial.count},
                {"big_fraction_radial", radial.fraction()},
                {"bodies_radial", radial.count},
                {"big_fraction_about_bed_centre", about_centre.fraction()},
                {"bed_centre", {cx, cy}},
                {"radial_segregation", {core.index, core.random_sd, core.index / core.random_sd}},
                {"core_small_fraction", {core.inner_fraction, core.outer_fraction, core.split}},
                {"axial_bands", {double(bands.bands), bands.contrast}},
                {"repose_angle", {repose}},
                {"fill_fraction", {(alpha - std::sin(alpha)) / kTwoPi}}};
    }

private:
    std::int64_t body_count() const {
        if (c_.integer("bodies") > 0) return c_.integer("bodies");
        const double volume = 0.5 * kTwoPi * radius_ * radius_ * length_;
        return std::max<std::int64_t>(1, std::llround(c_.real("fill") * volume * c_.real("bed_density")));
    }

    Config c_;
    double radius_, length_, omega_, d_, clearance_ = 0;
    RoughCylinder wall_;
    int small_ = -1, big_ = -1;
};

ProblemInfo rotating_drum_info() {
    ProblemInfo info;
    info.name = "rotating-drum";
    info.description = "tetrahedra in a rotating rough cylinder: radial and axial size segregation";
    info.schema = run_schema();
    // The whole bed turns, so lists age fast: a skin of 0.7 rebuilds them about a third as
    // often as 0.3 and runs ~25 % faster (benchmarks/results/rotating_drum.md, rotating-drum).
    info.schema.set_default("dt", "0.005").set_default("equilibration_steps", "0")
        .set_default("skin", "0.7");
    info.schema.real("diameter", 100, 4, 1e5, "sigma", "drum diameter D (wall spheres' centres)", true)
        .real("length", 200, 4, 1e6, "sigma", "drum length L (axis z, end caps at 0 and L)", true)
        .real("omega", 0.2, -10, 10, "1/tau", "angular velocity of the drum about +z")
        .real("gravity", 5, 0, 1e6, "sigma/tau^2", "gravitational acceleration (-y)")
        .integer("bodies", 0, 0, 1e9, "1", "number of tetrahedra (0: from fill and bed_density)")
        .real("fill", 0.5, 0, 0.9, "1", "fraction of the drum's volume the settled bed fills", true)
        .real("bed_density", 0.22, 0, 10, "sigma^-3",
              "tetrahedra per unit volume of the settled bed, used with fill (measured: see "
              "fill_fraction in the observables)", true)
        .real("big_fraction", 0.33, 0, 1, "1", "fraction of big tetrahedra (species at random)")
        .real("arm_small", 0.6, 0, 100, "sigma", "centre-to-sphere distance of small tetrahedra")
        .real("arm_big", 1.2, 0, 100, "sigma", "centre-to-sphere distance of big tetrahedra")
        .real("sphere_diameter", 1, 0, 100, "sigma", "diameter of every sphere", true)
        .real("sphere_mass", 1, 0, 1e6, "m", "mass of every sphere (a tetrahedron has 4)", true)
        .real("k_n", 1000, 0, 1e9, "epsilon/sigma^2", "overlap stiffness", true)
        .real("gamma_n", 5, 0, 1e9, "m/tau", "normal damping (sphere pairs and curved wall)")
        .real("gamma_s_big", 10, 0, 1e9, "m/tau", "sliding friction between spheres of big tetrahedra")
        .real("gamma_s_small", 2, 0, 1e9, "m/tau", "sliding friction between spheres of small tetrahedra")
        .real("gamma_s_mixed", 6, 0, 1e9, "m/tau",
              "sliding friction between a big and a small tetrahedron's spheres (the paper gives "
              "10 and 2 only; default their mean)")
        .real("gamma_s_wall", 10, 0, 1e9, "m/tau", "sliding friction with the curved wall")
        .real("mu_max", 0.5, 0, 10, "1", "Coulomb cap at the largest gamma_s (mu proportional to gamma_s)")
        .real("cap_gamma_n", 5, 0, 1e9, "m/tau", "normal damping of the smooth end caps")
        .choice("end_caps", "smooth", {"smooth", "rough"},
                "smooth (paper): normal damping only; rough: also spheres embedded on the curved "
                "wall's grid, turning with the drum")
        .real("wall_spacing", 2.2, 0, 100, "sigma", "spacing of the spheres embedded in the curved wall", true)
        .real("wall_sphere_diameter", 1, 0, 100, "sigma", "diameter of the wall spheres", true)
        .real("initial_speed", 0.1, 0, 100, "sigma/tau", "spread of the initial random velocities")
        .integer("axial_slices", 50, 1, 1e6, "1", "slices along the axis for species fractions")
        .integer("radial_shells", 20, 1, 1e6, "1", "shells about the axis for species fractions");
    info.schema.set_default("guard.max_force", "1e5");
    // About 6300 steps per revolution at omega 0.2 (paper: ~6400).
    // omega is structural: the rough wall's lattice turns through omega t, so a new omega would
    // jump the wall spheres through the bed.
    info.schema.structural({"diameter", "length", "omega", "bodies", "fill", "bed_density", "big_fraction",
                            "arm_small", "arm_big", "sphere_diameter", "sphere_mass", "wall_spacing",
                            "wall_sphere_diameter", "end_caps", "axial_slices", "radial_shells"})
        .adjustable({"gravity", "k_n", "gamma_n", "gamma_s_big", "gamma_s_small", "gamma_s_mixed",
                     "gamma_s_wall", "mu_max", "cap_gamma_n", "initial_speed"});
    info.presets["tiny"] = {{"diameter", "16"}, {"length", "12"}, {"bodies", "60"}, {"steps", "1000"},
                            {"sample_every", "100"}, {"axial_slices", "4"}, {"radial_shells", "4"}};
    info.presets["small"] = {{"diameter", "50"}, {"length", "24"}, {"bodies", "2600"},
                             {"steps", "252000"}, {"sample_every", "1260"},
                             {"axial_slices", "12"}, {"radial_shells", "25"},
                             {"output.every", "31500"}, {"progress_interval", "60"}};
    info.presets["short"] = {{"diameter", "100"}, {"length", "200"}, {"bodies", "136000"},
                             {"steps", "7200000"}, {"sample_every", "3150"},
                             {"output.every", "315000"}, {"checkpoint_every", "315000"},
                             {"progress_interval", "300"}};
    info.presets["long"] = {{"diameter", "80"}, {"length", "500"}, {"bodies", "103000"},
                            {"steps", "10000000"}, {"sample_every", "3150"},
                            {"axial_slices", "125"}, {"output.every", "315000"},
                            {"checkpoint_every", "315000"}, {"progress_interval", "300"}};
    info.factory = [](const Config& c) { return std::make_unique<RotatingDrum>(c); };
    return info;
}

}  // namespace

EMERGENT_REGISTER_PROBLEM(rotating_drum_info);

}  // namespace emergent::problems

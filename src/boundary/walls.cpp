// SPDX-License-Identifier: MIT
// Specular and thermal walls.
#include <cmath>
#include <sstream>

#include "boundary/wall_geometry.hpp"
#include "emergent/boundary.hpp"
#include "emergent/random.hpp"

namespace emergent {

namespace {

using boundary::for_each_crossing;
using boundary::WallGeometry;

/// x on a grid of 2^-30 (about 1e-9 sigma): the coin still flips with any visible change of
/// the impact point, but not with the round-off by which runs on different rank counts differ.
/// (An absolute grid, not relative bits: an impact on a wall at 0 has a coordinate of order
/// the round-off itself, whose bits are noise.)
std::uint64_t bits_of(double x) {
    return static_cast<std::uint64_t>(std::llround(std::ldexp(x, 30)));
}

/// Shared part of both walls: find the crossings, move each particle along its path to the
/// impact point, let the wall choose the new velocity, finish the step from there.
template <class NewVelocity>
void bounce(const WallGeometry& wall, ParticleStore& store, const BoundaryContext& context,
            const NewVelocity& new_velocity, WallExchange& exchange, std::string& fault,
            const std::string& name) {
    const double dt = context.dt;
    for_each_crossing(wall.shape, store.position.data(), store.n_owned(), [&](std::size_t i) {
        Vec3& x = store.position[i];
        Vec3& v = store.velocity[i];
        const double m = (*context.mass)[store.species[i]];
        const Vec3 start = x - dt * v;  // the drift moved it by v dt in a straight line
        double t = wall.impact_time(start, v, dt);
        Vec3 hit = start + t * v;
        if (!wall.on_fluid_side(start)) {
            // Its path this step was already bent by another wall (a corner): put it on this
            // wall at the nearest point, at the end of the step.
            t = dt;
            hit = x - wall.gap(x) * wall.normal(x);
        }
        const Vec3 n = wall.normal(hit);
        const Vec3 u = wall.velocity_at(hit, context.time);
        const Vec3 v_new = u + new_velocity(v - u, n, context.box ? context.box->primary_image(hit) : hit, store.id[i], m);
        x = hit + (dt - t) * v_new;
        // A grazing departure from a curved wall may end a hair beyond it: keep it on the wall.
        if (!wall.on_fluid_side(x)) x = hit + (1e-12 * (1 + std::fabs(wall.gap(x)))) * n;
        const Vec3 dp = m * (v_new - v);
        ++exchange.hits;
        exchange.momentum += dp;
        exchange.angular_momentum += wall.angular_component(hit, dp);
        exchange.energy += 0.5 * m * (dot(v_new, v_new) - dot(v, v));
        v = v_new;
        if (fault.empty() && (!wall.on_fluid_side(x) || !std::isfinite(x.x + x.y + x.z))) {
            std::ostringstream msg;
            msg << "particle id " << store.id[i] << " could not be returned inside " << name
                << " at step " << context.step << " (it crossed the region in one step?)";
            fault = msg.str();
        }
    });
}

class SpecularWall final : public BoundaryRule {
public:
    SpecularWall(const WallShape& shape, const WallMotion& motion) : wall_{shape, motion} {}
    std::string name() const override { return "specular wall"; }
    bool conservative() const override {
        return wall_.motion.omega == 0 && dot(wall_.motion.velocity, wall_.motion.velocity) == 0;
    }
    void apply(ParticleStore& store, const BoundaryContext& context, std::string& fault) override {
        auto reflect = [](const Vec3& w, const Vec3& n, const Vec3&, std::int64_t, double) {
            return w - (2 * dot(w, n)) * n;
        };
        bounce(wall_, store, context, reflect, exchange_, fault, name());
    }

private:
    WallGeometry wall_;
};

class ThermalWall final : public BoundaryRule {
public:
    ThermalWall(const WallShape& shape, double temperature, std::uint64_t seed,
                const WallMotion& motion)
        : wall_{shape, motion}, temperature_(temperature), seed_(seed) {}
    std::string name() const override { return "thermal wall"; }
    bool conservative() const override { return false; }
    void apply(ParticleStore& store, const BoundaryContext& context, std::string& fault) override {
        const double kT = temperature_;
        const std::uint64_t seed = seed_;
        const auto step = static_cast<std::uint64_t>(context.step);
        auto rethermalise = [=](const Vec3& w, const Vec3& n, const Vec3& hit, std::int64_t id,
                                double m) {
            // Reflection or reversal, from the bits of the impact point.
            const std::uint64_t h = mix64(bits_of(hit.x) ^ mix64(bits_of(hit.y) ^ mix64(bits_of(hit.z))));
            const double wn = dot(w, n);
            Vec3 out = (h >> 32) & 1 ? -1.0 * w : w - (2 * wn) * n;
            if (!(wn < 0)) out = n;  // grazing or outgoing: leave along the normal
            // s^2 m / kT is chi-squared with 4 degrees of freedom: -2 ln(u1 u2).
            const double u1 = uniform_open(seed, static_cast<std::uint64_t>(id), 2 * step);
            const double u2 = uniform_open(seed, static_cast<std::uint64_t>(id), 2 * step + 1);
            const double speed = std::sqrt(-2.0 * (kT / m) * std::log(u1 * u2));
            return (speed / std::sqrt(dot(out, out))) * out;
        };
        bounce(wall_, store, context, rethermalise, exchange_, fault, name());
    }

private:
    WallGeometry wall_;
    double temperature_;
    std::uint64_t seed_;
};

}  // namespace

std::unique_ptr<BoundaryRule> make_specular_wall(const WallShape& shape, const WallMotion& motion) {
    return std::make_unique<SpecularWall>(shape, motion);
}

std::unique_ptr<BoundaryRule> make_thermal_wall(const WallShape& shape, double temperature,
                                                std::uint64_t seed, const WallMotion& motion) {
    return std::make_unique<ThermalWall>(shape, temperature, seed, motion);
}

}  // namespace emergent

// SPDX-License-Identifier: MIT
// Specular and thermal walls: the bounce functors (boundary/bounce.hpp) run on the particles
// beyond the wall through the execution layer.
#include <sstream>

#include "boundary/bounce.hpp"
#include "boundary/wall_geometry.hpp"
#include "emergent/boundary.hpp"
#include "emergent/execution.hpp"

namespace emergent {

namespace {

using boundary::WallGeometry;

/// Shared part of both walls: the particles beyond the wall bounce off it with NewVelocity;
/// the wall's running tally and the first fault (a particle it could not return) are kept.
template <class NewVelocity>
void bounce(const WallGeometry& wall, const BackendParticles& p, const BoundaryContext& context,
            const NewVelocity& new_velocity, WallExchange& exchange, std::string& fault,
            const std::string& name) {
    const boundary::Bounce<NewVelocity> one{wall,
                                            new_velocity,
                                            p.position,
                                            p.velocity,
                                            p.species,
                                            p.mass,
                                            p.id,
                                            context.dt,
                                            context.time,
                                            context.box != nullptr,
                                            context.box ? *context.box : Box{}};
    boundary::BounceTally tally;
    tally.hits = exchange.hits;
    tally.momentum = exchange.momentum;
    tally.angular_momentum = exchange.angular_momentum;
    tally.energy = exchange.energy;
    boundary::with_crossing_test(wall.shape, [&](auto beyond) {
        const boundary::IsBeyond<decltype(beyond)> selected{beyond, p.position};
        tally = exec::transform_sum_if(p.target, p.n_owned, tally, selected, one);
    });
    exchange.hits = tally.hits;
    exchange.momentum = tally.momentum;
    exchange.angular_momentum = tally.angular_momentum;
    exchange.energy = tally.energy;
    if (fault.empty() && tally.first_fault < p.n_owned) {
        std::ostringstream msg;
        msg << "particle id " << exec::read_one(p.target, p.id + tally.first_fault) << " could not be returned inside "
            << name << " at step " << context.step << " (it crossed the region in one step?)";
        fault = msg.str();
    }
}

class SpecularWall final : public BoundaryRule {
public:
    SpecularWall(const WallShape& shape, const WallMotion& motion) : wall_{shape, motion} {}
    std::string name() const override { return "specular wall"; }
    bool conservative() const override {
        return wall_.motion.omega == 0 && dot(wall_.motion.velocity, wall_.motion.velocity) == 0;
    }
    void apply(const BackendParticles& p, const BoundaryContext& context, std::string& fault) override {
        bounce(wall_, p, context, boundary::Reflect{}, exchange_, fault, name());
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
    void apply(const BackendParticles& p, const BoundaryContext& context, std::string& fault) override {
        const boundary::Rethermalise rethermalise{temperature_, seed_,
                                                  static_cast<std::uint64_t>(context.step)};
        bounce(wall_, p, context, rethermalise, exchange_, fault, name());
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

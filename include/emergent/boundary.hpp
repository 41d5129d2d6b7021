// SPDX-License-Identifier: MIT
// Boundary rules: hard walls that act on particles which crossed them during the drift.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "emergent/backend_particles.hpp"
#include "emergent/box.hpp"
#include "emergent/macros.hpp"
#include "emergent/particle_store.hpp"

namespace emergent {

/// Shape of a wall. A plane normal to `axis` at `position`, with the particles on the side
/// `side` (+1: above, -1: below); or a cylinder about the axis through `centre` along `axis`,
/// of `radius`, with the particles outside it (side +1) or inside it (side -1).
struct WallShape {
    enum class Kind { Plane, Cylinder };
    Kind kind = Kind::Plane;
    int axis = 2;
    double position = 0;  ///< plane only
    Vec3 centre{0, 0, 0};  ///< cylinder only (its component along `axis` is ignored)
    double radius = 0;     ///< cylinder only
    int side = 1;

    static WallShape plane(int axis, double position, int side) {
        WallShape s;
        s.kind = Kind::Plane, s.axis = axis, s.position = position, s.side = side;
        return s;
    }
    static WallShape cylinder(int axis, const Vec3& centre, double radius, int side) {
        WallShape s;
        s.kind = Kind::Cylinder, s.axis = axis, s.centre = centre, s.radius = radius, s.side = side;
        return s;
    }
};

/// How a wall moves: a translation velocity plus a rotation rate about the wall's own axis
/// (for cylinders; the wall velocity at x is then velocity + omega axis x (x - centre)).
///
/// Optionally it starts slower: until time `start_until` it moves at `start_factor` times that
/// speed, then reaches full speed linearly over `ramp`. Which flow pattern forms depends on the
/// path to the final state (a sudden start and a slow approach can end in different patterns),
/// so the start is part of the experiment.
struct WallMotion {
    Vec3 velocity{0, 0, 0};
    double omega = 0;
    double start_factor = 1, start_until = 0, ramp = 0;

    /// Fraction of full speed at time t.
    EMERGENT_HD double factor(double t) const {
        if (t < start_until) return start_factor;
        if (t < start_until + ramp) return start_factor + (1 - start_factor) * (t - start_until) / ramp;
        return 1;
    }
    /// Integral of factor over [0, t]: the distance (or angle) travelled in units of full speed.
    EMERGENT_HD double travelled(double t) const {
        if (t < start_until) return start_factor * t;
        const double held = start_factor * start_until;
        if (t < start_until + ramp) {
            const double s = t - start_until;
            return held + start_factor * s + 0.5 * (1 - start_factor) * s * s / ramp;
        }
        return held + 0.5 * (1 + start_factor) * ramp + (t - start_until - ramp);
    }
};

/// What a wall gave to the particles that hit it, summed over hits (this rank's part): the
/// exchanges of momentum, of angular momentum about the wall's axis through its centre (for
/// planes: about the z axis through the origin), and of kinetic energy (heat into the fluid).
struct WallExchange {
    long long hits = 0;
    Vec3 momentum{0, 0, 0};
    double angular_momentum = 0;
    double energy = 0;
};

/// What a rule needs besides the particles.
struct BoundaryContext {
    double dt = 0;
    long long step = 0;  ///< the step being taken (keys the wall's random draws)
    /// The region; along its periodic axes a wall reads impact points in the primary image,
    /// so its choices do not depend on which image a rank happens to hold.
    const Box* box = nullptr;
    double time = 0;  ///< at the start of the drift (moving walls follow their schedule)
};

/// A rule applied to owned particles right after the drift. It finds each particle that
/// crossed its wall during the step, places it where it would be had it left the wall at the
/// impact instant with its new velocity, and records the exchange.
class BoundaryRule {
public:
    virtual ~BoundaryRule() = default;
    virtual std::string name() const = 0;
    /// False when the rule exchanges energy with the particles (thermal or moving walls).
    virtual bool conservative() const = 0;
    /// Applies the rule to the owned particles, where the back end holds them. A particle it
    /// cannot return to the fluid side (it jumped across the whole region, or is not finite)
    /// is described in `fault` (first one only).
    virtual void apply(const BackendParticles& particles, const BoundaryContext& context,
                       std::string& fault) = 0;
    /// Exchange summed over every hit since the rule was made, on this rank.
    const WallExchange& exchange() const { return exchange_; }
    /// Sets the tally (a run continued from a checkpoint).
    void set_exchange(const WallExchange& e) { exchange_ = e; }

protected:
    WallExchange exchange_;
};

/// Elastic (specular) wall: the velocity relative to the wall has its normal component reversed.
std::unique_ptr<BoundaryRule> make_specular_wall(const WallShape& shape,
                                                 const WallMotion& motion = {});

/// Thermal wall at `temperature`: a particle that reaches it leaves with a speed (relative to
/// the wall) drawn from the distribution of the speeds with which particles of a fluid at that
/// temperature strike a wall, p(s) ~ s^3 exp(-m s^2 / 2kT), and a direction that is either the
/// reflection or the reversal of its incoming direction. Which of the two is a deterministic
/// function of the impact point, so sensitive to it that it acts as a fair coin; the speed is
/// drawn from (seed, particle id, step). The moving wall's own velocity is added.
///
/// Why that speed distribution: incoming directions of an equilibrium fluid at T are spread as
/// |cos(theta)| about the normal, independent of the speed, and both reflection and reversal
/// keep that spread; with speeds drawn as above the outgoing flux is exactly the incoming flux
/// of a fluid at T, so the wall and a fluid at its temperature are in detailed balance.
std::unique_ptr<BoundaryRule> make_thermal_wall(const WallShape& shape, double temperature,
                                                std::uint64_t seed, const WallMotion& motion = {});

}  // namespace emergent

// SPDX-License-Identifier: MIT
// Bussi–Donadio–Parrinello stochastic velocity rescaling.
//
// Chosen as the default thermostat because it samples the canonical ensemble exactly (unlike
// Berendsen), needs only the global kinetic energy (one reduction, any rank count), conserves
// momentum, and perturbs the dynamics only through one global factor per step, so flow fields
// and transport are disturbed far less than by Langevin noise on every particle.
#include <cmath>
#include <random>
#include <sstream>

#include "emergent/error.hpp"
#include "emergent/random.hpp"
#include "emergent/thermostat.hpp"

namespace emergent {

namespace {

class BussiThermostat final : public Thermostat {
public:
    BussiThermostat(double temperature, double tau, std::uint64_t seed)
        : temperature_(temperature), tau_(tau), seed_(seed) {}

    std::string name() const override { return "bussi"; }
    double target_temperature() const override { return temperature_; }

    double scale_factor(double kinetic, double dof, long long step, double dt) const override {
        if (!(kinetic > 0)) return 1.0;
        // One generator per step, seeded from (seed, step): identical on all ranks and after
        // a restart, whatever happened before.
        std::mt19937_64 rng(mix64(seed_ ^ mix64(static_cast<std::uint64_t>(step))));
        std::normal_distribution<double> normal(0.0, 1.0);
        const double c = std::exp(-dt / tau_);
        const double target = 0.5 * dof * temperature_;
        const double r1 = normal(rng);
        // Sum of dof-1 squared normals is chi-squared(dof-1) = 2 Gamma((dof-1)/2, 1).
        const double rest =
            dof > 1 ? 2.0 * std::gamma_distribution<double>(0.5 * (dof - 1), 1.0)(rng) : 0.0;
        const double ratio = target / (dof * kinetic);
        const double alpha2 = c + (1 - c) * ratio * (r1 * r1 + rest) +
                              2 * r1 * std::sqrt(c * (1 - c) * ratio);
        // alpha2 = (sqrt(c) + r1 sqrt((1-c) ratio))^2 + (1-c) ratio rest >= 0.
        return std::sqrt(alpha2);
    }

private:
    double temperature_, tau_;
    std::uint64_t seed_;
};

}  // namespace

std::unique_ptr<Thermostat> make_bussi_thermostat(double temperature, double tau,
                                                  std::uint64_t seed) {
    if (!(temperature > 0) || !(tau > 0)) {
        std::ostringstream msg;
        msg << "bussi thermostat: temperature=" << temperature << " and tau=" << tau
            << " must be > 0";
        throw InputError(msg.str());
    }
    return std::make_unique<BussiThermostat>(temperature, tau, seed);
}

}  // namespace emergent

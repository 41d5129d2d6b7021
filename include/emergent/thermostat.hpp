// SPDX-License-Identifier: MIT
// Thermostats that act on the whole system by rescaling velocities.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

namespace emergent {

/// A global thermostat: from the total kinetic energy it returns the factor by which all
/// velocities are scaled at the end of a step. Global rescaling conserves total momentum and
/// leaves the local (hydrodynamic) dynamics untouched apart from a slow uniform rescale.
class Thermostat {
public:
    virtual ~Thermostat() = default;
    virtual std::string name() const = 0;
    virtual double target_temperature() const = 0;
    /// kinetic: total kinetic energy; dof: degrees of freedom; the same on every rank, and so
    /// must be the result (random numbers come from (seed, step)).
    virtual double scale_factor(double kinetic, double dof, long long step, double dt) const = 0;
};

/// Canonical-sampling velocity rescaling of Bussi, Donadio and Parrinello, J. Chem. Phys. 126,
/// 014101 (2007): the kinetic energy follows a stochastic relaxation with time constant tau
/// towards the canonical distribution at `temperature`.
std::unique_ptr<Thermostat> make_bussi_thermostat(double temperature, double tau,
                                                  std::uint64_t seed);

}  // namespace emergent

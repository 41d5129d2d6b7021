// SPDX-License-Identifier: MIT
// The Bussi thermostat relaxes the kinetic energy with its time constant tau. Bussi, Donadio and
// Parrinello, J. Chem. Phys. 126, 014101 (2007), eq. (A7): over a step dt the mean kinetic
// energy obeys <K(t + dt)> = c K(t) + (1 - c) K_target, c = exp(-dt / tau), so from K0
//     <K(t)> = K_target + (K0 - K_target) exp(-t / tau)
// exactly at every step (the noise averages out). Checked on the thermostat's own function and
// on an ideal gas run by the engine (no forces: only the thermostat changes K).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "emergent/simulation.hpp"
#include "emergent/thermostat.hpp"

using namespace emergent;

namespace {

/// Mean and standard error of the mean over realisations.
std::pair<double, double> mean_and_error(const std::vector<double>& x) {
    double m = 0, v = 0;
    for (double y : x) m += y;
    m /= double(x.size());
    for (double y : x) v += (y - m) * (y - m);
    return {m, std::sqrt(v / double(x.size() - 1) / double(x.size()))};
}

}  // namespace

TEST(BussiRelaxation, MeanKineticEnergyDecaysWithTimeConstantTau) {
    // K0 = 4 K_target and K0 = K_target / 5, dof = 3000 (1001 particles), tau = 0.4, dt = 0.005:
    // 256 realisations (thermostat seeds) followed for 3 tau (0.2 s).
    const double dof = 3000, temperature = 1.5, tau = 0.4, dt = 0.005;
    const double target = 0.5 * dof * temperature;
    const int steps = 240, realisations = 256;
    for (double k0 : {4 * target, 0.2 * target}) {
        std::vector<std::vector<double>> k(steps + 1, std::vector<double>(realisations));
        for (int r = 0; r < realisations; ++r) {
            const auto thermostat = make_bussi_thermostat(temperature, tau, 1000 + r);
            double kinetic = k0;
            k[0][r] = kinetic;
            for (int n = 1; n <= steps; ++n) {
                const double alpha = thermostat->scale_factor(kinetic, dof, n, dt);
                kinetic *= alpha * alpha;
                k[n][r] = kinetic;
            }
        }
        // <K> at tau / 2, tau, 2 tau and 3 tau within 5 standard errors of the mean over the
        // realisations (each ~0.25 % of K_target here; a chance of 6e-7 per check for a correct
        // thermostat, and the draws are seeded). A relaxation twice too fast or too slow is off
        // by ~0.2 (K0 - K_target) at tau: hundreds of standard errors.
        for (int n : {40, 80, 160, 240}) {
            const auto [mean, error] = mean_and_error(k[n]);
            const double expected = target + (k0 - target) * std::exp(-n * dt / tau);
            std::printf(
                "K0/K_target = %.1f, t/tau = %.1f: <K>/K_target = %.5f +- %.5f (expected %.5f)\n",
                k0 / target, n * dt / tau, mean / target, error / target, expected / target);
            EXPECT_NEAR(mean, expected, 5 * error) << "t = " << n * dt;
        }
        // tau itself, from the mean's decay between 0 and tau: tau_fit = -t / ln(excess ratio).
        // Its error is the relative error of the excess at t = tau (the log's slope is 1 there):
        // 5 standard errors of <K(tau)> over |K(tau) - K_target|.
        const auto [mean, error] = mean_and_error(k[80]);
        const double excess = (mean - target) / (k0 - target);
        const double tau_fit = -80 * dt / std::log(excess);
        EXPECT_NEAR(tau_fit, tau, tau * 5 * error / std::abs(mean - target)) << "K0 = " << k0;
    }
}

TEST(BussiRelaxation, IdealGasInTheEngineRelaxesWithTau) {
    // 512 free particles (no forces) at T0 = 4 thermostatted to T = 1 with tau = 0.25, dt =
    // 0.005; measure() reports T = 2 K / dof, so <T(t)> = T + (T0 - T) exp(-t / tau) exactly
    // (assign_thermal_velocities gives K0 exactly). 32 realisations (thermostat seeds).
    const double t0 = 4, temperature = 1, tau = 0.25;
    const int realisations = 32;
    const std::vector<int> checks{25, 50, 100};  // t = tau / 2, tau, 2 tau
    std::vector<std::vector<double>> t(checks.size(), std::vector<double>(realisations));
    double dt = 0;
    for (int r = 0; r < realisations; ++r) {
        RunSettings rs;
        Simulation sim(MPI_COMM_WORLD, rs);
        Box box;
        box.hi = {16, 16, 16};
        sim.set_box(box);
        sim.set_species_masses({2.0});
        sim.set_thermostat(make_bussi_thermostat(temperature, tau, 500 + r));
        for (int i = 0; i < 512; ++i)
            sim.add_particle({1 + 2.0 * (i % 8), 1 + 2.0 * ((i / 8) % 8), 1 + 2.0 * (i / 64)},
                             {0, 0, 0}, 0, i);
        sim.assign_thermal_velocities(t0, 7 + r);
        sim.initialise();
        dt = sim.dt();
        ASSERT_NEAR(sim.measure().temperature, t0, 1e-10 * t0);  // exact but for the sum's rounding
        for (int n = 1, c = 0; n <= checks.back(); ++n) {
            sim.step(false);
            if (n == checks[c]) t[c++][r] = sim.measure().temperature;
        }
    }
    for (std::size_t c = 0; c < checks.size(); ++c) {
        const auto [mean, error] = mean_and_error(t[c]);
        const double expected = temperature + (t0 - temperature) * std::exp(-checks[c] * dt / tau);
        std::printf("ideal gas, t/tau = %.1f: <T> = %.4f +- %.4f (expected %.4f)\n",
                    checks[c] * dt / tau, mean, error, expected);
        // 5 standard errors (each ~0.4 % of T; Student's t with 31 degrees of freedom beyond 5:
        // 2e-5, and the run is seeded); a thermostat given dt / 2 or 2 dt misses by ~30 errors.
        EXPECT_NEAR(mean, expected, 5 * error) << "t = " << checks[c] * dt;
    }
}

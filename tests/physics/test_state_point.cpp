// SPDX-License-Identifier: MIT
// WCA fluid at rho = 0.8, T = 1 against the LAMMPS reference state point.
#include <gtest/gtest.h>

#include <cmath>

#include "emergent/block_average.hpp"
#include "support/scene_fixture.hpp"

using namespace emergent;

TEST(StatePoint, WcaPressureAndEnergyMatchLammps) {
    // Reference (shared/reference/lammps-wca.md, in.wca_state): N = 32000, Nose-Hoover,
    // 200 tau averaged: U/N = 0.82634 +- 0.00014, P = 6.6087 +- 0.0008, T = 1.00028 +- 0.00022.
    const double u_ref = 0.82634, u_err = 0.00014, p_ref = 6.6087, p_err = 0.0008;
    // N = 4000 here; WCA finite-size effects on U and P at this N are O(1/N) ~ 3e-4, below our
    // own statistical error. Canonical averages do not depend on which thermostat samples them.
    auto sim = emergent::testing::make_scene(MPI_COMM_WORLD, "lj-fluid",
                                             {"n_cells=10", "thermostat=bussi", "seed=2024"});
    for (int k = 0; k < 2000; ++k) sim->step(false);
    BlockAverage u, p, t;
    for (int k = 1; k <= 20000; ++k) {
        const bool sample = k % 50 == 0;
        sim->step(sample);
        if (!sample) continue;
        const ThermoSample s = sim->measure();
        u.add(s.potential);
        p.add(s.pressure);
        t.add(s.temperature);
    }
    // Three combined standard errors: a false alarm has probability ~0.3 % per quantity.
    const double su = std::hypot(u.standard_error(), u_err);
    const double sp = std::hypot(p.standard_error(), p_err);
    EXPECT_NEAR(u.mean(), u_ref, 3 * su);
    EXPECT_NEAR(p.mean(), p_ref, 3 * sp);
    EXPECT_NEAR(t.mean(), 1.0, 3 * t.standard_error() + 1e-4);
    std::printf("U/N = %.5f +- %.5f (LAMMPS %.5f)  P = %.4f +- %.4f (LAMMPS %.4f)  T = %.5f\n",
                u.mean(), u.standard_error(), u_ref, p.mean(), p.standard_error(), p_ref,
                t.mean());
}

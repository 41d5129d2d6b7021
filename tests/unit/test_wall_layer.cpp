// SPDX-License-Identifier: MIT
// The wall-layer thermostat: exact properties of one rescaling.
#include <gtest/gtest.h>

#include <mpi.h>

#include <random>

#include "emergent/wall_layer.hpp"

using namespace emergent;

TEST(WallLayerThermostat, RescalesOnlyTheLayerToItsTemperatureWithoutDriftAlongTheWall) {
    // After one rescaling the layer's particles have zero mean momentum along the wall, keep
    // their mean motion across it, and have the wall temperature over 3n - 2 degrees of freedom;
    // particles outside are untouched and the reported energy is the kinetic energy change.
    // All exact up to rounding.
    ParticleStore store;
    std::mt19937_64 rng(7);
    std::normal_distribution<double> g(0.0, 1.5);
    std::uniform_real_distribution<double> z(0.0, 10.0);
    for (int k = 0; k < 400; ++k)
        store.add_owned({0, 0, z(rng)}, {g(rng) + 0.3, g(rng) - 0.7, g(rng) + 0.2}, k % 2, k);
    const std::vector<double> mass{1.0, 2.5};
    const ParticleStore before = store;
    WallLayerThermostat layer(2, 0.0, 2.0, 4.0, 10);

    layer.apply(host_view(store, mass), MPI_COMM_WORLD, 7);  // not a multiple of the interval: nothing
    for (std::size_t i = 0; i < store.n_owned(); ++i) EXPECT_EQ(store.velocity[i].x, before.velocity[i].x);

    layer.apply(host_view(store, mass), MPI_COMM_WORLD, 20);
    double m = 0, px = 0, py = 0, pz = 0, pz0 = 0, twice_k = 0, n = 0, dk = 0;
    for (std::size_t i = 0; i < store.n_owned(); ++i) {
        const double mi = mass[store.species[i]];
        const Vec3 v = store.velocity[i], v0 = before.velocity[i];
        dk += 0.5 * mi * (dot(v, v) - dot(v0, v0));
        if (store.position[i].z >= 2.0) {
            EXPECT_EQ(v.x, v0.x);
            EXPECT_EQ(v.z, v0.z);
            continue;
        }
        m += mi, n += 1;
        px += mi * v.x, py += mi * v.y, pz += mi * v.z, pz0 += mi * v0.z;
        twice_k += mi * dot(v, v);
    }
    ASSERT_GT(n, 40);
    EXPECT_NEAR(px / m, 0.0, 1e-12);
    EXPECT_NEAR(py / m, 0.0, 1e-12);
    // Motion across the wall is scaled, not removed: same sign and the common factor.
    EXPECT_GT(pz * pz0, 0.0);
    EXPECT_NEAR(twice_k / (3 * n - 2), 4.0, 1e-12);
    EXPECT_NEAR(layer.energy(), dk, 1e-10 * std::fabs(dk) + 1e-12);
}

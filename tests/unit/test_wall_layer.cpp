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

TEST(WallLayerThermostat, MeasuredApartThenRescaledIsApplyBitForBit) {
    // The engine sums the layers due at a step in one collective: each layer measured, the sums
    // added, each rescaled. For layers that share no particle that is apply() one after the
    // other, bit for bit; layers that may share one say so (overlaps), and are applied in turn.
    ParticleStore store;
    std::mt19937_64 rng(11);
    std::normal_distribution<double> g(0.0, 1.0);
    std::uniform_real_distribution<double> z(0.0, 10.0);
    for (int k = 0; k < 300; ++k) store.add_owned({0, 0, z(rng)}, {g(rng), g(rng), g(rng)}, 0, k);
    const std::vector<double> mass{1.0};
    WallLayerThermostat hot(2, -1.0, 2.0, 2.0, 1), cold(2, 8.0, 11.0, 0.5, 1);
    WallLayerThermostat hot2 = hot, cold2 = cold;
    ParticleStore one_by_one = store, together = store;
    hot.apply(host_view(one_by_one, mass), MPI_COMM_WORLD, 3);
    cold.apply(host_view(one_by_one, mass), MPI_COMM_WORLD, 3);
    double sums[2 * WallLayerThermostat::kSums];
    hot2.measure(host_view(together, mass), sums);
    cold2.measure(host_view(together, mass), sums + WallLayerThermostat::kSums);
    MPI_Allreduce(MPI_IN_PLACE, sums, 2 * WallLayerThermostat::kSums, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    hot2.rescale(host_view(together, mass), sums);
    cold2.rescale(host_view(together, mass), sums + WallLayerThermostat::kSums);
    for (std::size_t i = 0; i < store.n_owned(); ++i)
        for (int d = 0; d < 3; ++d) ASSERT_EQ(one_by_one.velocity[i][d], together.velocity[i][d]) << i;
    EXPECT_EQ(hot.energy(), hot2.energy());
    EXPECT_EQ(cold.energy(), cold2.energy());
    EXPECT_FALSE(hot.overlaps(cold));
    EXPECT_TRUE(hot.overlaps(WallLayerThermostat(2, 1.5, 3.0, 1.0, 1)));
    EXPECT_TRUE(hot.overlaps(WallLayerThermostat(0, 20.0, 21.0, 1.0, 1)));  // another axis
    EXPECT_TRUE(hot.due(7) && !WallLayerThermostat(2, 0.0, 1.0, 1.0, 5).due(7));
}

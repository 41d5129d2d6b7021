// SPDX-License-Identifier: MIT
// The particle arrays in a back end's memory (here the checking host memory): copies both
// ways are exact and counted, the host's copy is poisoned while a field lives on the back end,
// the engine's functors run on the back end's arrays, and arrays follow the store's size.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "emergent/execution.hpp"
#include "emergent/gpu.hpp"
#include "particles/particle_mirror.hpp"
#include "integrate/kick_drift.hpp"

using namespace emergent;

namespace {

ParticleStore random_store(std::size_t n, unsigned seed, bool rigid) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-5, 5);
    ParticleStore s;
    for (std::size_t i = 0; i < n; ++i)
        s.add_owned({u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}, static_cast<int>(i % 2),
                    static_cast<std::int64_t>(1000 + i));
    if (rigid) s.enable_rigid_fields();
    for (std::size_t i = 0; i < n; ++i) s.force[i] = {u(rng), u(rng), u(rng)};
    return s;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

bool same_bits(const ParticleStore& a, const ParticleStore& b) {
    return same_bits(a.position, b.position) && same_bits(a.velocity, b.velocity) &&
           same_bits(a.force, b.force) && same_bits(a.species, b.species) && same_bits(a.id, b.id) &&
           same_bits(a.body, b.body) && same_bits(a.orientation, b.orientation);
}

}  // namespace

TEST(ParticleMirror, RoundTripIsExactAndCounted) {
    for (bool rigid : {false, true}) {
        ParticleStore store = random_store(1000, 1, rigid);
        const ParticleStore original = store;
        exec::ParticleMirror mirror(exec::separate_host_memory(), true);
        const exec::Transfers before = exec::transfers();
        mirror.to_backend(store, kAllFields);
        int fields = 0;
        std::size_t bytes = 0;
        store.for_each_field([&](const FieldSpan& f) {
            ++fields;
            bytes += f.element_bytes * store.size();
        });
        EXPECT_EQ(exec::transfers().arrays - before.arrays, static_cast<unsigned>(fields));
        EXPECT_EQ(exec::transfers().array_bytes - before.array_bytes, bytes);
        EXPECT_TRUE(same_bits(store, original)) << "a copy to the back end leaves the host's valid";
        mirror.written_on_backend(store, kAllFields);
        EXPECT_FALSE(same_bits(store, original)) << "the host copy should be poisoned";
        mirror.to_host(store, kAllFields);
        EXPECT_TRUE(same_bits(store, original)) << (rigid ? "rigid" : "plain");
        EXPECT_EQ(exec::transfers().arrays - before.arrays, 2u * fields);
    }
}

TEST(ParticleMirror, PoisonShowsAReadBetweenSyncs) {
    ParticleStore store = random_store(100, 2, false);
    exec::ParticleMirror mirror(exec::separate_host_memory(), true);
    mirror.to_backend(store, kPosition | kSpecies | kVelocity);
    mirror.written_on_backend(store, kPosition | kSpecies);
    // What a host loop that forgot to sync would read: NaN positions, a species (like an id,
    // body or image count) far below any valid value, -1 included (it means a free particle).
    EXPECT_TRUE(std::isnan(store.position[17].x));
    EXPECT_LT(store.species[17], -1000000);
    EXPECT_FALSE(std::isnan(store.velocity[17].x)) << "fields only read there are left alone";
    EXPECT_EQ(mirror.backend_only(), unsigned(kPosition | kSpecies));
    exec::ParticleMirror plain(exec::separate_host_memory(), false);
    ParticleStore kept = random_store(100, 2, false);
    plain.written_on_backend(kept, kPosition);
    EXPECT_FALSE(std::isnan(kept.position[17].x)) << "poisoning only in the checking variant";
}

TEST(ParticleMirror, FunctorsRunOnTheBackendArrays) {
    ParticleStore store = random_store(500, 3, false);
    ParticleStore reference = store;
    const std::vector<double> inverse_mass{1.0, 0.5};
    const integrate::KickDrift on_host{reference.position.data(), reference.velocity.data(),
                                       reference.force.data(), reference.species.data(),
                                       inverse_mass.data(), 0.0025, 0.005};
    exec::for_each(exec::Host{}, reference.size(), on_host);

    exec::ParticleMirror mirror(exec::separate_host_memory(), true);
    mirror.to_backend(store, kPosition | kVelocity | kForce | kSpecies);
    const integrate::KickDrift on_backend{mirror.array<Vec3>(kPosition), mirror.array<Vec3>(kVelocity),
                                          mirror.array<Vec3>(kForce), mirror.array<int>(kSpecies),
                                          inverse_mass.data(), 0.0025, 0.005};
    exec::for_each(exec::Host{}, mirror.size(), on_backend);
    mirror.written_on_backend(store, kPosition | kVelocity);
    mirror.to_host(store, kPosition | kVelocity);
    EXPECT_TRUE(same_bits(store.position, reference.position));
    EXPECT_TRUE(same_bits(store.velocity, reference.velocity));
}

TEST(ParticleMirror, CopiesOnlyStaleFields) {
    ParticleStore store = random_store(50, 6, false);
    exec::ParticleMirror mirror(exec::separate_host_memory(), true);
    const exec::Transfers before = exec::transfers();
    mirror.to_backend(store, kPosition | kVelocity);
    mirror.to_backend(store, kPosition | kVelocity);  // both current there already
    mirror.to_host(store, kPosition | kVelocity);     // and here
    EXPECT_EQ(exec::transfers().arrays - before.arrays, 2u);
    store.position[3].x += 1;  // host code moves a particle
    mirror.written_on_host(kPosition);
    EXPECT_EQ(mirror.host_only(), mirror.host_only() | kPosition);
    mirror.to_backend(store, kPosition | kVelocity);
    EXPECT_EQ(exec::transfers().arrays - before.arrays, 3u);
    EXPECT_EQ(mirror.array<Vec3>(kPosition)[3].x, store.position[3].x);
}

TEST(ParticleMirror, ArraysFollowTheStoreSize) {
    ParticleStore store = random_store(64, 4, false);
    exec::ParticleMirror mirror(exec::separate_host_memory(), false);
    mirror.to_backend(store, kAllFields);
    mirror.written_on_backend(store, kVelocity);  // a kernel moved the particles on
    // Host code that resizes the store (ghosts for the decomposition) while velocities live
    // on the back end only would lose them: refused.
    store.resize_ghosts(200);
    EXPECT_THROW(mirror.to_backend(store, kPosition), std::logic_error);
    EXPECT_THROW(mirror.to_host(store, kVelocity), std::logic_error) << "sizes differ";
    store.resize_ghosts(0);
    mirror.array<Vec3>(kVelocity)[5].y = 7.5;
    mirror.to_host(store, kVelocity);
    EXPECT_EQ(store.velocity[5].y, 7.5);
    // Now the resize is fine (far more than the 1/32 room): everything is sent at the new size.
    store.resize_ghosts(200);
    for (std::size_t i = store.n_owned(); i < store.size(); ++i) store.position[i] = {1, 2, double(i)};
    mirror.written_on_host(kPosition);
    mirror.to_backend(store, kPosition | kVelocity);
    EXPECT_EQ(mirror.size(), store.size());
    EXPECT_EQ(mirror.array<Vec3>(kVelocity)[5].y, 7.5);
    EXPECT_EQ(mirror.array<Vec3>(kPosition)[250].z, 250.0);
    EXPECT_EQ(mirror.host_only() & (kPosition | kVelocity), 0u);
    EXPECT_NE(mirror.host_only() & kForce, 0u) << "not sent at the new size";
}

// A build on the back end drops and re-adds particles: while the resize is deferred only the
// store's counts follow, the host arrays take the last size once at the end (poisoned, their
// values being on the back end), and reading or sending host values in between is refused.
TEST(ParticleMirror, DeferredResizeSizesTheHostArraysOnceAtTheEnd) {
    ParticleStore store = random_store(64, 5, false);
    exec::ParticleMirror mirror(exec::separate_host_memory(), true);
    mirror.to_backend(store, kAllFields);
    {
        const exec::ParticleMirror::DeferredResize deferred(mirror, store);
        mirror.resize_on_backend(store, 10, 0);
        EXPECT_EQ(store.size(), 10u);
        EXPECT_EQ(store.position.size(), 64u) << "the host array is not resized yet";
        mirror.resize_on_backend(store, 70, 5);
        EXPECT_EQ(store.n_owned(), 70u);
        EXPECT_EQ(store.n_ghost(), 5u);
        EXPECT_EQ(mirror.size(), 75u);
        EXPECT_THROW(mirror.to_host(store, kPosition), std::logic_error);
        EXPECT_THROW(store.add_owned({0, 0, 0}, {0, 0, 0}, 0, 1), std::logic_error);
        mirror.written_on_host(kVelocity);
        EXPECT_THROW(mirror.to_backend(store, kVelocity), std::logic_error);
        mirror.written_on_backend(store, kVelocity);
    }
    EXPECT_FALSE(store.resize_deferred());
    EXPECT_EQ(store.position.size(), 75u);
    EXPECT_EQ(store.velocity.size(), 75u);
    EXPECT_TRUE(std::isnan(store.position[3].x)) << "poisoned: the values are on the back end";
    mirror.array<Vec3>(kPosition)[72].z = 2.5;
    mirror.to_host(store, kPosition);
    EXPECT_EQ(store.position[72].z, 2.5);
}

TEST(ParticleMirror, CudaMemoryRefusedClearlyWithoutDevice) {
    if (gpu::device_present()) GTEST_SKIP() << "a CUDA device is present";
    try {
        exec::cuda_device_memory();
        FAIL() << "got CUDA memory without a device";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("GPU was requested"), std::string::npos) << e.what();
    }
}

TEST(ParticleMirror, TablesAreCopiedWhenTheyChange) {
    exec::ParticleMirror mirror(exec::separate_host_memory(), true);
    std::vector<double> mass{1.0, 2.0};
    const exec::Transfers before = exec::transfers();
    const double* on_backend = mirror.table(0, mass);
    EXPECT_NE(on_backend, mass.data()) << "the kernels must read the back end's copy";
    EXPECT_EQ(on_backend[1], 2.0);
    mirror.table(0, mass);
    EXPECT_EQ(exec::transfers().arrays - before.arrays, 1u) << "unchanged: not copied again";
    mass.push_back(15.0);
    EXPECT_EQ(mirror.table(0, mass)[2], 15.0);
    EXPECT_EQ(exec::transfers().arrays - before.arrays, 2u);
}

// reserve makes room in every array without changing the particles, so a set-up's additions
// up to that count move nothing; fit_capacity gives the room back.
TEST(ParticleStore, ReserveMakesRoomWithoutChangingParticles) {
    ParticleStore s = random_store(10, 7, false);
    const ParticleStore before = s;
    s.reserve(1000);
    EXPECT_TRUE(same_bits(s, before));
    EXPECT_EQ(s.n_owned(), 10u);
    EXPECT_GE(s.position.capacity(), 1000u);
    EXPECT_GE(s.velocity.capacity(), 1000u);
    EXPECT_GE(s.force.capacity(), 1000u);
    EXPECT_GE(s.id.capacity(), 1000u);
    const Vec3* data = s.position.data();
    for (int i = 0; i < 990; ++i) s.add_owned({0, 0, 0}, {0, 0, 0}, 0, 2000 + i);
    EXPECT_EQ(s.position.data(), data);
    EXPECT_EQ(s.n_owned(), 1000u);
    s.reserve(10);  // less than held: nothing changes
    EXPECT_EQ(s.position.data(), data);
    s.fit_capacity();
    EXPECT_EQ(s.position.capacity(), 1000u);
}

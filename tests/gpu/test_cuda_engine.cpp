// SPDX-License-Identifier: MIT
// The engine on a CUDA device (Simulation with backend=cuda): against an independent all-pairs
// reference on the host, its energy conservation, bitwise repeatability, its guards, and the
// WCA state point against LAMMPS. Skipped (reported as skipped) without a device; without one
// the only check is that asking for the device fails with one clear line. CI runs them on the
// checking back end (see tested_backend()).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <string>

#include "emergent/error.hpp"
#include "emergent/force_term.hpp"
#include "emergent/gpu.hpp"
#include "emergent/simulation.hpp"
#include "emergent/thermostat.hpp"
#include "emergent/block_average.hpp"
#include "support/fluid_start.hpp"

using namespace emergent;

namespace {

/// Velocity Verlet with all pairs at nearest image, Lennard-Jones written out here from its
/// textbook form: shares no code with the engine's evaluator, list or integrator.
struct AllPairsReference {
    Vec3 box;
    double rc, shift;
    std::vector<Vec3> x, v, f;
    double potential = 0, virial = 0;

    AllPairsReference(const fixtures::FluidStart& s, double cutoff) : box(s.box), rc(cutoff), x(s.x), v(s.v) {
        const double sr6 = std::pow(1 / rc, 6);
        shift = 4 * (sr6 * sr6 - sr6);
        forces();
    }
    void forces() {
        f.assign(x.size(), Vec3{0, 0, 0});
        potential = virial = 0;
        for (std::size_t i = 0; i < x.size(); ++i)
            for (std::size_t j = i + 1; j < x.size(); ++j) {
                Vec3 d = x[i] - x[j];
                for (int a = 0; a < 3; ++a) d[a] -= box[a] * std::nearbyint(d[a] / box[a]);
                const double r2 = dot(d, d);
                if (r2 >= rc * rc) continue;
                const double sr6 = 1 / (r2 * r2 * r2);
                const double fr = 24 * (2 * sr6 * sr6 - sr6) / r2;
                f[i] += fr * d;
                f[j] -= fr * d;
                potential += 4 * (sr6 * sr6 - sr6) - shift;
                virial += fr * r2;
            }
    }
    void step(double dt) {
        for (std::size_t i = 0; i < x.size(); ++i) {
            v[i] += 0.5 * dt * f[i];
            x[i] += dt * v[i];
        }
        forces();
        for (std::size_t i = 0; i < x.size(); ++i) v[i] += 0.5 * dt * f[i];
    }
};

double rms(const std::vector<Vec3>& a) {
    double s = 0;
    for (const Vec3& u : a) s += dot(u, u);
    return std::sqrt(s / a.size());
}

/// The back end under test: cuda, or with EMERGENT_GPU_TESTS_BACKEND=checking its host twin
/// (the same functors on separate host memory, the host's copy poisoned between syncs), so CI
/// runs these tests without a device (test gpu_tests_on_checking).
Backend tested_backend() {
    const char* b = std::getenv("EMERGENT_GPU_TESTS_BACKEND");
    return b && std::string(b) == "checking" ? Backend::Checking : Backend::Cuda;
}

struct Settings {
    double cutoff = 1.122462048309373, skin = 0.3, dt = 0.005;
    Backend backend = tested_backend();
};

/// A Lennard-Jones fluid from `start` through the engine (ids in start's order), initialised.
std::unique_ptr<Simulation> fluid(const fixtures::FluidStart& start, const Settings& s) {
    RunSettings run;
    run.dt = s.dt;
    run.skin = s.skin;
    run.backend = s.backend;
    run.list_layout = ListLayout::Full;
    auto sim = std::make_unique<Simulation>(MPI_COMM_SELF, run);
    Box box;
    box.hi = start.box;
    sim->set_box(box);
    sim->set_species_masses({1.0});
    sim->add_force(make_lennard_jones(1.0, 1.0, s.cutoff, false));
    for (std::size_t i = 0; i < start.x.size(); ++i)
        sim->add_particle(box.primary_image(start.x[i]), start.v[i], 0, static_cast<std::int64_t>(i));
    sim->initialise();
    return sim;
}

/// Unwrapped positions (and velocities) in id order.
std::vector<Vec3> by_id(const Simulation& sim, bool velocities) {
    const ParticleStore& s = sim.particles();
    const Vec3 len = sim.box().length();
    std::vector<Vec3> out(s.n_owned());
    for (std::size_t i = 0; i < s.n_owned(); ++i) {
        Vec3 x = s.position[i];
        for (int a = 0; a < 3; ++a) x[a] += s.image[i][a] * len[a];
        out[static_cast<std::size_t>(s.id[i])] = velocities ? s.velocity[i] : x;
    }
    return out;
}

/// Largest distance between a reference position and the engine's, as periodic images.
double max_difference(const std::vector<Vec3>& a, const std::vector<Vec3>& b, const Vec3& box) {
    double worst = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        Vec3 d = a[i] - b[i];
        for (int k = 0; k < 3; ++k) d[k] -= box[k] * std::nearbyint(d[k] / box[k]);
        worst = std::max(worst, std::sqrt(dot(d, d)));
    }
    return worst;
}

#define SKIP_WITHOUT_DEVICE() \
    if (tested_backend() == Backend::Cuda && !gpu::device_present()) \
    GTEST_SKIP() << "no CUDA device on this machine"

}  // namespace

TEST(CudaEngine, RefusesClearlyWithoutADevice) {
    if (gpu::device_present()) GTEST_SKIP() << "a CUDA device is present";
    const auto s = fixtures::fcc_fluid(4, 0.8, 1.0, 0.1, 3);
    try {
        fluid(s, Settings{});
        FAIL() << "ran on a CUDA device without one";
    } catch (const std::exception& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        EXPECT_NE(what.find("cuda"), std::string::npos) << what;
    }
}

class CudaVersusAllPairs : public ::testing::TestWithParam<double> {};

TEST_P(CudaVersusAllPairs, TrajectoriesAgreeOver100Steps) {
    SKIP_WITHOUT_DEVICE();
    const double cutoff = GetParam();
    // 2048 atoms at rho = 0.8, T = 1.5: a liquid; jitter breaks the lattice's symmetry.
    const auto start = fixtures::fcc_fluid(8, 0.8, 1.5, 0.2, 17);
    Settings s;
    s.cutoff = cutoff;
    s.skin = 0.08;  // small: the list is rebuilt (and the particles reordered) many times
    auto sim = fluid(start, s);
    AllPairsReference ref(start, cutoff);
    const ThermoSample t0 = sim->measure();
    // Same pair sums in another order: round-off only.
    EXPECT_NEAR(t0.potential * t0.n, ref.potential, 1e-12 * std::abs(ref.potential) + 1e-12);
    for (int k = 0; k < 100; ++k) {
        ref.step(s.dt);
        sim->step(false);
    }
    const double dx = max_difference(by_id(*sim, false), ref.x, start.box);
    const double dv = max_difference(by_id(*sim, true), ref.v, Vec3{1e300, 1e300, 1e300});
    // Both differ only in the order of the force sums (~1e-16 relative per step); over 100
    // steps of a dense liquid (0.5 tau, a few Lyapunov times at most) that grows to ~1e-13. A
    // bound of 1e-9 relative (to the box side, to the rms speed) leaves room for that growth;
    // a missed pair or a wrong image gives 1e-3 and more.
    EXPECT_LT(dx, 1e-9 * start.box.x) << "max position difference";
    EXPECT_LT(dv, 1e-9 * rms(ref.v)) << "max velocity difference";
    EXPECT_GE(sim->rebuilds(), 4) << "the test must cross several rebuilds";
    std::printf("rc %.4f: max |dx| %.3e, max |dv| %.3e, %lld list builds\n", cutoff, dx, dv, sim->rebuilds());
}

// WCA (the benchmark's interaction) and LJ at rc = 2.5 (~57 neighbours per atom).
INSTANTIATE_TEST_SUITE_P(Cutoffs, CudaVersusAllPairs, ::testing::Values(1.122462048309373, 2.5));

TEST(CudaEngine, ConservesEnergy) {
    SKIP_WITHOUT_DEVICE();
    // The CPU test's bounds (physics/test_conservation.cpp, from the LAMMPS reference: 4000
    // atoms, rho 0.8, T 1, dt 0.005 fluctuate by ~3.4e-4 per atom): total energy per atom
    // every 20 steps over 4000 steps after 1000 to melt the lattice.
    auto sim = fluid(fixtures::fcc_fluid(10, 0.8, 1.0, 0.0, 5), Settings{});
    for (int k = 0; k < 1000; ++k) sim->step(false);
    auto total = [&] {
        sim->step(true);
        return sim->measure().total;
    };
    const double e0 = total();
    double worst = 0, ts = 0, es = 0, tt = 0, te = 0;
    int n = 0;
    for (int k = 1; k <= 200; ++k) {
        for (int j = 0; j < 19; ++j) sim->step(false);
        const double e = total(), t = k * 20 * 0.005;
        worst = std::max(worst, std::abs(e - e0));
        ts += t, es += e, tt += t * t, te += t * e, ++n;
    }
    const double slope = (n * te - ts * es) / (n * tt - ts * ts);
    EXPECT_LT(worst, 1e-3);
    EXPECT_LT(std::abs(slope), 2e-5);
    std::printf("energy per atom over 20 tau: max |dE| %.3e, slope %.3e per tau\n", worst, slope);
}

TEST(CudaEngine, SameInputGivesBitwiseTheSameTrajectory) {
    SKIP_WITHOUT_DEVICE();
    // No atomics in any sum, stable radix sorts and fixed reduction trees: on one device with
    // the same N the run is reproducible bit for bit.
    const auto start = fixtures::fcc_fluid(10, 0.8, 1.5, 0.1, 23);
    Settings s;
    s.skin = 0.1;
    auto a = fluid(start, s), b = fluid(start, s);
    for (int k = 0; k < 2000; ++k) {
        a->step(false);
        b->step(false);
    }
    EXPECT_GE(a->rebuilds(), 20);
    const auto xa = by_id(*a, false), xb = by_id(*b, false), va = by_id(*a, true), vb = by_id(*b, true);
    EXPECT_EQ(0, std::memcmp(xa.data(), xb.data(), xa.size() * sizeof(Vec3)));
    EXPECT_EQ(0, std::memcmp(va.data(), vb.data(), va.size() * sizeof(Vec3)));
}

TEST(CudaEngine, AgreesWithTheCheckingBackEndToRoundOff) {
    SKIP_WITHOUT_DEVICE();
    // The same functors on the host (the checking back end) and on the device: the first
    // sample's sums differ only in their order of additions.
    const auto start = fixtures::fcc_fluid(8, 0.8, 1.2, 0.1, 41);
    Settings s;
    auto device = fluid(start, s);
    s.backend = Backend::Checking;
    auto host = fluid(start, s);
    const ThermoSample a = device->measure(), b = host->measure();
    EXPECT_NEAR(a.potential, b.potential, 1e-13 * std::abs(b.potential));
    EXPECT_NEAR(a.pressure, b.pressure, 1e-12 * std::abs(b.pressure));
    EXPECT_NEAR(a.kinetic, b.kinetic, 1e-13 * std::abs(b.kinetic));
}

namespace {

/// The message of the InstabilityError that `steps` steps (guards every step) raise, or "".
std::string instability_message(Simulation& sim, long steps, double max_force) {
    try {
        for (long k = 0; k < steps; ++k) {
            sim.step(false);
            sim.check_guards(GuardLimits{max_force});
        }
    } catch (const InstabilityError& e) {
        std::printf("%s\n", e.what());
        return e.what();
    }
    return "";
}

}  // namespace

TEST(CudaEngine, StopsWithAClearMessageWhenTheRunBlowsUp) {
    SKIP_WITHOUT_DEVICE();
    // T = 50 with dt = 0.2 (the CPU guard test's case): particles step deep into each other and
    // the forces pass the bound (1e5) long before they overflow.
    Settings s;
    s.dt = 0.2;
    auto sim = fluid(fixtures::fcc_fluid(6, 0.8, 50.0, 0.0, 29), s);
    const std::string message = instability_message(*sim, 2000, 1e5);
    EXPECT_TRUE(message.find("exceeds guard.max_force") != std::string::npos ||
                message.find("within one step") != std::string::npos)
        << message;
}

TEST(CudaEngine, StopsOnNonFiniteState) {
    SKIP_WITHOUT_DEVICE();
    auto start = fixtures::fcc_fluid(6, 0.8, 1.0, 0.0, 31);
    start.v[17].y = std::nan("");
    auto sim = fluid(start, Settings{});
    const std::string message = instability_message(*sim, 10, 1e5);
    EXPECT_TRUE(message.find("non-finite") != std::string::npos) << message;
}

TEST(CudaEngine, WcaStatePointMatchesLammps) {
    SKIP_WITHOUT_DEVICE();
    // Longer runs are compared by their averages: the reference (shared/reference/lammps-wca.md,
    // in.wca_state) is N = 32000, Nose-Hoover, 200 tau: U/N = 0.82634 +- 0.00014,
    // P = 6.6087 +- 0.0008, T = 1.00028 +- 0.00022. Here the same N with the engine's Bussi
    // thermostat on the device every step (canonical averages do not depend on which thermostat
    // samples them), 100 tau after 10 tau of equilibration.
    const double u_ref = 0.82634, u_err = 0.00014, p_ref = 6.6087, p_err = 0.0008;
    auto sim = fluid(fixtures::fcc_fluid(20, 0.8, 1.0, 0.0, 37), Settings{});
    sim->set_thermostat(make_bussi_thermostat(1.0, 0.1, 2024));
    for (int k = 0; k < 2000; ++k) sim->step(false);
    BlockAverage u, p, t;
    for (int k = 0; k < 1000; ++k) {
        for (int j = 0; j < 19; ++j) sim->step(false);
        sim->step(true);
        const ThermoSample th = sim->measure();
        u.add(th.potential);
        p.add(th.pressure);
        t.add(th.temperature);
    }
    // Three combined standard errors: a false alarm has probability ~0.3 % per quantity.
    EXPECT_NEAR(u.mean(), u_ref, 3 * std::hypot(u.standard_error(), u_err));
    EXPECT_NEAR(p.mean(), p_ref, 3 * std::hypot(p.standard_error(), p_err));
    EXPECT_NEAR(t.mean(), 1.0, 3 * t.standard_error() + 1e-4);
    std::printf("engine on the device, Bussi: U/N = %.5f +- %.5f (LAMMPS %.5f)  P = %.4f +- %.4f "
                "(LAMMPS %.4f)  T = %.5f +- %.5f\n",
                u.mean(), u.standard_error(), u_ref, p.mean(), p.standard_error(), p_ref, t.mean(),
                t.standard_error());
}

// SPDX-License-Identifier: MIT
// The GPU path against an independent all-pairs reference on the host, and its energy
// conservation in double and mixed precision. Skipped (reported as skipped) without a device;
// without one, the only check is that asking for the GPU fails with a clear message.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <tuple>

#include "emergent/error.hpp"
#include "emergent/gpu.hpp"
#include "emergent/thermostat.hpp"
#include "observe/block_average.hpp"
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

double max_difference(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    double worst = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const Vec3 d = a[i] - b[i];
        worst = std::max(worst, std::sqrt(dot(d, d)));
    }
    return worst;
}

#define SKIP_WITHOUT_DEVICE() \
    if (!gpu::device_present()) GTEST_SKIP() << "no CUDA device on this machine"

}  // namespace

TEST(GpuPath, RefusesClearlyWithoutADevice) {
    if (gpu::device_present()) GTEST_SKIP() << "a CUDA device is present";
    const auto s = fixtures::fcc_fluid(4, 0.8, 1.0, 0.1, 3);
    gpu::PairSystemSpec spec;
    spec.box = s.box;
    try {
        gpu::PeriodicPairSystem sys(spec, s.x, s.v);
        FAIL() << "constructed a GPU system without a device";
    } catch (const std::runtime_error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("GPU was requested but"), std::string::npos) << what;
    }
}

class GpuVersusAllPairs : public ::testing::TestWithParam<std::tuple<double, int>> {};

TEST_P(GpuVersusAllPairs, TrajectoriesAgreeOver100Steps) {
    SKIP_WITHOUT_DEVICE();
    const double cutoff = std::get<0>(GetParam());
    // 2048 atoms at rho = 0.8, T = 1.5: a liquid; jitter breaks the lattice's symmetry.
    const auto start = fixtures::fcc_fluid(8, 0.8, 1.5, 0.2, 17);
    gpu::PairSystemSpec spec;
    spec.box = start.box;
    spec.cutoff = cutoff;
    spec.skin = 0.08;  // small: the list is rebuilt (and the particles reordered) many times
    spec.dt = 0.005;
    spec.lanes_per_particle = std::get<1>(GetParam());
    gpu::PeriodicPairSystem sys(spec, start.x, start.v);
    AllPairsReference ref(start, cutoff);
    // The list statistics (they choose the threads per particle) count every pair within the
    // list cutoff twice, at the start positions.
    std::size_t pairs = 0;
    const double rl = cutoff + spec.skin;
    for (std::size_t i = 0; i < start.x.size(); ++i)
        for (std::size_t j = i + 1; j < start.x.size(); ++j) {
            Vec3 d = start.x[i] - start.x[j];
            for (int a = 0; a < 3; ++a) d[a] -= spec.box[a] * std::nearbyint(d[a] / spec.box[a]);
            pairs += dot(d, d) < rl * rl;
        }
    EXPECT_DOUBLE_EQ(sys.list_stats().mean_neighbours, 2.0 * pairs / start.x.size());

    const gpu::Thermo t0 = sys.thermo();
    // Same pair sums in another order: round-off only.
    EXPECT_NEAR(t0.potential, ref.potential, 1e-12 * std::abs(ref.potential) + 1e-12);
    EXPECT_NEAR(t0.virial, ref.virial, 1e-12 * std::abs(ref.virial));

    for (int k = 0; k < 100; ++k) ref.step(spec.dt);
    sys.run(100);
    const auto x = sys.positions(), v = sys.velocities();
    const double dx = max_difference(x, ref.x), dv = max_difference(v, ref.v);
    // Both codes differ only in the order of the force sums (~1e-16 relative per step);
    // over 100 steps of a dense liquid (0.5 tau, a few Lyapunov times at most) that grows to
    // ~1e-13. The bound of 1e-9 relative (to the box side, to the rms speed) leaves
    // room for that growth; a missed pair or a wrong image gives 1e-3 and more.
    EXPECT_LT(dx, 1e-9 * spec.box.x) << "max position difference";
    EXPECT_LT(dv, 1e-9 * rms(ref.v)) << "max velocity difference";
    EXPECT_GE(sys.list_stats().builds, 4) << "the test must cross several rebuilds";
    RecordProperty("max_position_difference", std::to_string(dx));
    RecordProperty("max_velocity_difference", std::to_string(dv));
    RecordProperty("list_builds", std::to_string(sys.list_stats().builds));
    std::printf("rc %.4f, %d lanes per particle: max |dx| %.3e, max |dv| %.3e, %ld list builds\n",
                cutoff, sys.list_stats().lanes, dx, dv, sys.list_stats().builds);
}

// WCA (the benchmark's interaction) and LJ at rc = 2.5 (~57 neighbours per atom), with the
// automatic threads per particle (2 and 8 here), one thread, and a whole warp per particle.
INSTANTIATE_TEST_SUITE_P(Cutoffs, GpuVersusAllPairs,
                         ::testing::Values(std::make_tuple(1.122462048309373, 0), std::make_tuple(2.5, 0),
                                           std::make_tuple(2.5, 1), std::make_tuple(2.5, 32)));

namespace {

struct Drift {
    double worst = 0, slope = 0;
};

/// Total energy per atom sampled every 20 steps over 4000 steps after 1000 to melt the lattice.
Drift energy_drift(gpu::Precision precision) {
    const auto start = fixtures::fcc_fluid(10, 0.8, 1.0, 0.0, 5);
    gpu::PairSystemSpec spec;
    spec.box = start.box;
    spec.precision = precision;
    gpu::PeriodicPairSystem sys(spec, start.x, start.v);
    sys.run(1000);
    const double n_atoms = double(sys.size());
    auto total = [&] {
        const gpu::Thermo t = sys.thermo();
        return (t.kinetic + t.potential) / n_atoms;
    };
    const double e0 = total();
    Drift d;
    double ts = 0, es = 0, tt = 0, te = 0;
    int n = 0;
    for (int k = 1; k <= 200; ++k) {
        sys.run(20);
        const double e = total(), t = k * 20 * spec.dt;
        d.worst = std::max(d.worst, std::abs(e - e0));
        ts += t, es += e, tt += t * t, te += t * e, ++n;
    }
    d.slope = (n * te - ts * es) / (n * tt - ts * ts);
    return d;
}

}  // namespace

TEST(GpuPath, ConservesEnergyInDoubleAndMixedPrecision) {
    SKIP_WITHOUT_DEVICE();
    // The CPU test's bounds (physics/test_conservation.cpp, from the LAMMPS reference: 4000
    // atoms, rho 0.8, T 1, dt 0.005 fluctuate by ~3.4e-4 per atom).
    const Drift dbl = energy_drift(gpu::Precision::Double);
    EXPECT_LT(dbl.worst, 1e-3);
    EXPECT_LT(std::abs(dbl.slope), 2e-5);
    // Mixed: each pair force carries float round-off (~6e-8 relative), a random error far below
    // the integrator's own; the same bounds must hold, and the drift is reported beside double's.
    const Drift mix = energy_drift(gpu::Precision::Mixed);
    EXPECT_LT(mix.worst, 1e-3);
    EXPECT_LT(std::abs(mix.slope), 2e-5);
    RecordProperty("double_max_abs_energy_change", std::to_string(dbl.worst));
    RecordProperty("double_energy_slope_per_tau", std::to_string(dbl.slope));
    RecordProperty("mixed_max_abs_energy_change", std::to_string(mix.worst));
    RecordProperty("mixed_energy_slope_per_tau", std::to_string(mix.slope));
    std::printf("energy per atom over 20 tau: double max |dE| %.3e slope %.3e; mixed max |dE| %.3e slope %.3e\n",
                dbl.worst, dbl.slope, mix.worst, mix.slope);
}

TEST(GpuPath, RejectsABoxTooSmallForTheCellGrid) {
    SKIP_WITHOUT_DEVICE();
    const auto s = fixtures::fcc_fluid(2, 0.8, 1.0, 0.1, 3);  // side 3.4 < 3 x (2.5 + 0.3)
    gpu::PairSystemSpec spec;
    spec.box = s.box;
    spec.cutoff = 2.5;
    EXPECT_THROW(gpu::PeriodicPairSystem(spec, s.x, s.v), std::invalid_argument);
}

TEST(GpuPath, SameInputGivesBitwiseTheSameTrajectory) {
    SKIP_WITHOUT_DEVICE();
    // No atomics in any sum, a stable radix sort and fixed reduction trees: on one device with
    // the same N, lanes and block size, the run is reproducible bit for bit.
    const auto start = fixtures::fcc_fluid(10, 0.8, 1.5, 0.1, 23);
    gpu::PairSystemSpec spec;
    spec.box = start.box;
    spec.skin = 0.1;
    gpu::PeriodicPairSystem a(spec, start.x, start.v), b(spec, start.x, start.v);
    a.run(2000);
    b.run(2000);
    EXPECT_GE(a.list_stats().builds, 20);
    const auto xa = a.positions(), xb = b.positions(), va = a.velocities(), vb = b.velocities();
    EXPECT_EQ(0, std::memcmp(xa.data(), xb.data(), xa.size() * sizeof(Vec3)));
    EXPECT_EQ(0, std::memcmp(va.data(), vb.data(), va.size() * sizeof(Vec3)));
}

namespace {

/// The message of the InstabilityError that `steps` steps of `spec` from `start` raise, or ""
/// when the run goes on.
std::string instability_message(const gpu::PairSystemSpec& spec, const fixtures::FluidStart& start, long steps) {
    gpu::PeriodicPairSystem sys(spec, start.x, start.v);
    try {
        sys.run(steps);
    } catch (const InstabilityError& e) {
        std::printf("%s\n", e.what());
        return e.what();
    }
    return "";
}

}  // namespace

TEST(GpuPath, StopsWithAClearMessageWhenTheRunBlowsUp) {
    SKIP_WITHOUT_DEVICE();
    // T = 50 with dt = 0.2 (the CPU guard test's case): particles step deep into each other and
    // the forces pass the bound (1e5) long before they overflow.
    const auto start = fixtures::fcc_fluid(6, 0.8, 50.0, 0.0, 29);
    gpu::PairSystemSpec spec;
    spec.box = start.box;
    spec.dt = 0.2;
    EXPECT_EQ(instability_message(spec, start, 2000).rfind("run stopped: a force on the GPU exceeds max_force", 0),
              0u);
}

TEST(GpuPath, StopsOnNonFiniteStateWithoutAForceBound) {
    SKIP_WITHOUT_DEVICE();
    auto start = fixtures::fcc_fluid(6, 0.8, 1.0, 0.0, 31);
    start.v[17].y = std::nan("");
    gpu::PairSystemSpec spec;
    spec.box = start.box;
    spec.max_force = 0;
    EXPECT_NE(instability_message(spec, start, 10).find("became non-finite after step 0"), std::string::npos);
}

TEST(GpuPath, WcaStatePointMatchesLammps) {
    SKIP_WITHOUT_DEVICE();
    // Longer runs are compared by their averages: the reference (shared/reference/lammps-wca.md,
    // in.wca_state) is N = 32000, Nose-Hoover, 200 tau: U/N = 0.82634 +- 0.00014,
    // P = 6.6087 +- 0.0008, T = 1.00028 +- 0.00022. Here the same N with the engine's Bussi
    // thermostat applied on the GPU every step (canonical averages do not depend on which
    // thermostat samples them), 100 tau after 10 tau of equilibration.
    const double u_ref = 0.82634, u_err = 0.00014, p_ref = 6.6087, p_err = 0.0008;
    const auto start = fixtures::fcc_fluid(20, 0.8, 1.0, 0.0, 37);
    gpu::PairSystemSpec spec;
    spec.box = start.box;
    gpu::PeriodicPairSystem sys(spec, start.x, start.v);
    sys.set_thermostat(make_bussi_thermostat(1.0, 0.1, 2024));
    sys.run(2000);
    const double n = double(sys.size()), volume = spec.box.x * spec.box.y * spec.box.z;
    BlockAverage u, p, t;
    for (int k = 0; k < 1000; ++k) {
        sys.run(20);
        const gpu::Thermo th = sys.thermo();
        u.add(th.potential / n);
        p.add((2 * th.kinetic + th.virial) / (3 * volume));
        t.add(2 * th.kinetic / (3 * n - 3));
    }
    // Three combined standard errors: a false alarm has probability ~0.3 % per quantity.
    EXPECT_NEAR(u.mean(), u_ref, 3 * std::hypot(u.standard_error(), u_err));
    EXPECT_NEAR(p.mean(), p_ref, 3 * std::hypot(p.standard_error(), p_err));
    EXPECT_NEAR(t.mean(), 1.0, 3 * t.standard_error() + 1e-4);
    std::printf("GPU, Bussi: U/N = %.5f +- %.5f (LAMMPS %.5f)  P = %.4f +- %.4f (LAMMPS %.4f)  T = %.5f +- %.5f\n",
                u.mean(), u.standard_error(), u_ref, p.mean(), p.standard_error(), p_ref, t.mean(),
                t.standard_error());
}

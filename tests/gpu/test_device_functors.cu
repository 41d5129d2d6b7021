// SPDX-License-Identifier: MIT
// The engine's per-particle functors run as CUDA grids give what they give as host loops: the
// guards' state check, momenta, a thermal wall's bounces with their tally, the wall-layer
// rescaling. Compiling this file (in CI too) shows the functors are device code; running it
// needs a device (skipped without one).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "boundary/bounce.hpp"
#include "emergent/execution.hpp"
#include "emergent/gpu.hpp"
#include "emergent/cuda_algorithms.cuh"
#include "gpu/device_buffer.cuh"
#include "support/device_arrays.cuh"
#include "integrate/particle_sums.hpp"
#include "thermostat/wall_layer_rescale.hpp"

using namespace emergent;
using fixtures::on_device;
using fixtures::on_host;

namespace {

/// Particles in a slab 0 < z < 10, some moved just past the wall at z = 0 by a drift of dt.
struct Slab {
    std::vector<Vec3> x, v;
    std::vector<int> species;
    std::vector<std::int64_t> id;
    std::vector<double> mass{1.0, 2.0};
    explicit Slab(std::size_t n) {
        std::mt19937_64 rng(21);
        std::uniform_real_distribution<double> u(-1, 1);
        for (std::size_t i = 0; i < n; ++i) {
            const Vec3 vi{u(rng), u(rng), u(rng)};
            Vec3 xi{5 * u(rng), 5 * u(rng), 5 + 5 * u(rng)};
            // Half a drift past the wall if moving towards it: it crossed during the last drift
            // of dt = 0.005 from the fluid side.
            if (i % 7 == 0) xi.z = 0.0025 * vi.z;
            x.push_back(xi);
            v.push_back(vi);
            species.push_back(static_cast<int>(i % 2));
            id.push_back(static_cast<std::int64_t>(100 + i));
        }
    }
};

double max_difference(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    double d = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
        for (int k = 0; k < 3; ++k) d = std::max(d, std::fabs(a[i][k] - b[i][k]));
    return d;
}

}  // namespace

#define SKIP_WITHOUT_DEVICE() \
    if (!gpu::device_present()) GTEST_SKIP() << "no CUDA device on this machine"

TEST(DeviceFunctors, ThermalWallBouncesAsOnTheHost) {
    SKIP_WITHOUT_DEVICE();
    gpu::select_device();
    Slab host(20000);
    auto x = on_device(host.x), v = on_device(host.v);
    auto species = on_device(host.species);
    auto id = on_device(host.id);
    auto mass = on_device(host.mass);
    const boundary::WallGeometry wall{WallShape::plane(2, 0.0, +1), {}};
    const boundary::Rethermalise thermal{1.5, 77, 1234};
    const double dt = 0.005;
    const boundary::BeyondPlane<2> beyond{1.0, 0.0};
    const boundary::Bounce<boundary::Rethermalise> on_host_bounce{
        wall, thermal, host.x.data(), host.v.data(), host.species.data(), host.mass.data(),
        host.id.data(), dt, 0.0, false, Box{}};
    const boundary::Bounce<boundary::Rethermalise> on_device_bounce{
        wall, thermal, x.data(), v.data(), species.data(), mass.data(), id.data(), dt, 0.0, false, Box{}};
    const auto h = exec::transform_sum_if(exec::Host{}, host.x.size(), boundary::BounceTally{},
                                          boundary::IsBeyond<decltype(beyond)>{beyond, host.x.data()},
                                          on_host_bounce);
    const auto d = exec::transform_sum_if(exec::Cuda{}, host.x.size(), boundary::BounceTally{},
                                          boundary::IsBeyond<decltype(beyond)>{beyond, x.data()},
                                          on_device_bounce);
    EXPECT_EQ(d.hits, h.hits);
    EXPECT_GT(h.hits, 1000);  // about half of every 7th particle: ~1430
    EXPECT_EQ(d.first_fault, h.first_fault);
    // Per particle the same arithmetic; the device may contract multiply-adds differently, so
    // agreement to a few ulps of the velocities (order 1), not bitwise.
    EXPECT_LT(max_difference(on_host(x), host.x), 1e-13);
    EXPECT_LT(max_difference(on_host(v), host.v), 1e-13);
    EXPECT_NEAR(d.energy, h.energy, 1e-9 * std::fabs(h.energy));
}

TEST(DeviceFunctors, GuardsMomentaAndWallLayerAsOnTheHost) {
    SKIP_WITHOUT_DEVICE();
    gpu::select_device();
    Slab host(30001);
    std::vector<Vec3> f(host.x.size(), Vec3{1, -2, 3});
    std::vector<Int3> image(host.x.size(), Int3{1, 0, -1});
    f[23456].y = std::numeric_limits<double>::infinity();
    auto x = on_device(host.x), v = on_device(host.v), df = on_device(f);
    auto species = on_device(host.species);
    auto mass = on_device(host.mass);
    auto dimage = on_device(image);
    const std::size_t n = host.x.size();
    EXPECT_EQ(exec::first_index(exec::Cuda{}, n, integrate::UnfitState{x.data(), v.data(), df.data(), 0}),
              exec::first_index(exec::Host{}, n, integrate::UnfitState{host.x.data(), host.v.data(), f.data(), 0}));
    const Vec3 box{10, 10, 10};
    const auto ph = exec::transform_sum<integrate::Momenta>(
        exec::Host{}, n, integrate::FreeMomenta{host.x.data(), host.v.data(), image.data(),
                                                host.species.data(), host.mass.data(), nullptr, box});
    const auto pd = exec::transform_sum<integrate::Momenta>(
        exec::Cuda{}, n, integrate::FreeMomenta{x.data(), v.data(), dimage.data(), species.data(),
                                                mass.data(), nullptr, box});
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(pd.linear[k], ph.linear[k], 1e-9);
        EXPECT_NEAR(pd.angular[k], ph.angular[k], 1e-8);
    }
    const thermostat::InLayer layer{2, 0.0, 1.5};
    const auto sh = exec::transform_sum<thermostat::LayerSums>(
        exec::Host{}, n, thermostat::LayerMember{host.x.data(), host.v.data(), host.species.data(), host.mass.data(), layer});
    const auto sd = exec::transform_sum<thermostat::LayerSums>(
        exec::Cuda{}, n, thermostat::LayerMember{x.data(), v.data(), species.data(), mass.data(), layer});
    EXPECT_EQ(sd.count, sh.count);
    EXPECT_NEAR(sd.twice_kinetic, sh.twice_kinetic, 1e-10 * sh.twice_kinetic);
    exec::for_each(exec::Host{}, n, thermostat::RescaleLayer{host.x.data(), host.v.data(), layer, 0.9, {0.1, 0, 0}});
    exec::for_each(exec::Cuda{}, n, thermostat::RescaleLayer{x.data(), v.data(), layer, 0.9, {0.1, 0, 0}});
    EXPECT_LT(max_difference(on_host(v), host.v), 1e-15);
}

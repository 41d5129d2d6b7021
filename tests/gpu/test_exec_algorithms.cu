// SPDX-License-Identifier: MIT
// The execution layer's CUDA reductions, scans and sorts against its host versions (which
// unit_tests check against plain loops), on the same inputs; the transfers they count.
// Skipped (reported as skipped) without a device.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "emergent/execution.hpp"
#include "emergent/gpu.hpp"
#include "emergent/cuda_algorithms.cuh"
#include "gpu/device_buffer.cuh"
#include "support/device_arrays.cuh"
#include "support/execution_cases.hpp"

using namespace emergent;
using fixtures::on_device;
using fixtures::on_host;

namespace {

struct Read {
    const double* v;
    EMERGENT_HD double operator()(std::size_t i) const { return v[i]; }
};

}  // namespace

#define SKIP_WITHOUT_DEVICE() \
    if (!gpu::device_present()) GTEST_SKIP() << "no CUDA device on this machine"

TEST(CudaExecution, SumAgreesWithHostAndRepeatsBitwise) {
    SKIP_WITHOUT_DEVICE();
    gpu::select_device();
    for (std::size_t n : {1ul, 1000ul, 1000003ul}) {
        const auto v = fixtures::spread_values(n, 11);
        auto d = on_device(v);
        const double host = exec::transform_sum<double>(exec::Host{}, n, [&](std::size_t i) { return v[i]; });
        double magnitude = 0;
        for (double x : v) magnitude += std::fabs(x);
        const std::uint64_t before = exec::transfers().scalars;
        const double a = exec::transform_sum<double>(exec::Cuda{}, n, Read{d.data()});
        const double b = exec::transform_sum<double>(exec::Cuda{}, n, Read{d.data()});
        // Another order of additions: each partial sum rounds by at most eps times the sum of
        // magnitudes, n - 1 of them.
        EXPECT_LE(std::fabs(a - host), n * std::numeric_limits<double>::epsilon() * magnitude) << n;
        EXPECT_EQ(a, b) << "run to run on one device";
        EXPECT_EQ(exec::transfers().scalars - before, 2u) << "one scalar read back per sum";
    }
}

TEST(CudaExecution, MaxIsExactAndKeepsNan) {
    SKIP_WITHOUT_DEVICE();
    gpu::select_device();
    auto v = fixtures::spread_values(300001, 12);
    auto d = on_device(v);
    EXPECT_EQ(exec::transform_max(exec::Cuda{}, v.size(), -1e300, Read{d.data()}),
              exec::transform_max(exec::Host{}, v.size(), -1e300, [&](std::size_t i) { return v[i]; }));
    EXPECT_EQ(exec::transform_max(exec::Cuda{}, 0, -7.0, Read{d.data()}), -7.0);
    v[299999] = std::numeric_limits<double>::quiet_NaN();
    auto with_nan = on_device(v);
    EXPECT_TRUE(std::isnan(exec::transform_max(exec::Cuda{}, v.size(), 0.0, Read{with_nan.data()})));
}

TEST(CudaExecution, ScanAgreesWithHostInPlace) {
    SKIP_WITHOUT_DEVICE();
    gpu::select_device();
    std::vector<std::uint32_t> keys, values;
    fixtures::repeated_keys(1000001, 6, 13, keys, values);
    auto d = on_device(keys);
    gpu::DeviceBuffer<std::uint32_t> out(keys.size());
    const std::uint32_t total = exec::exclusive_scan(exec::Cuda{}, d.data(), out.data(), keys.size());
    const std::uint32_t in_place = exec::exclusive_scan(exec::Cuda{}, d.data(), d.data(), keys.size());
    std::vector<std::uint32_t> expected(keys.size());
    EXPECT_EQ(total, exec::exclusive_scan(exec::Host{}, keys.data(), expected.data(), keys.size()));
    EXPECT_EQ(in_place, total);
    EXPECT_EQ(on_host(out), expected);
    EXPECT_EQ(on_host(d), expected);
}

TEST(CudaExecution, SortPairsGivesTheHostOrder) {
    SKIP_WITHOUT_DEVICE();
    gpu::select_device();
    for (int bits : {8, 20, 32}) {
        std::vector<std::uint32_t> keys, values;
        fixtures::repeated_keys(500001, bits, 14, keys, values);
        auto dk = on_device(keys);
        auto dv = on_device(values);
        exec::sort_pairs(exec::Cuda{}, dk.data(), dv.data(), keys.size(), bits);
        exec::sort_pairs(exec::Host{}, keys.data(), values.data(), keys.size(), bits);
        EXPECT_EQ(on_host(dk), keys) << bits << " key bits";
        EXPECT_EQ(on_host(dv), values) << bits << " key bits (stable: equal keys keep their order)";
    }
}

TEST(CudaExecution, WideKeySortAndQueuedScanGiveTheHostResults) {
    SKIP_WITHOUT_DEVICE();
    gpu::select_device();
    std::vector<std::uint64_t> keys;
    std::vector<std::uint32_t> values;
    fixtures::cell_and_id_keys(500001, 18, 17, keys, values);
    auto dk = on_device(keys);
    auto dv = on_device(values);
    exec::sort_pairs(exec::Cuda{}, dk.data(), dv.data(), keys.size(), 32 + 18);
    exec::sort_pairs(exec::Host{}, keys.data(), values.data(), keys.size(), 32 + 18);
    EXPECT_EQ(on_host(dk), keys);
    EXPECT_EQ(on_host(dv), values);
    const std::uint64_t read_before = exec::transfers().scalars;
    exec::exclusive_scan_queued(exec::Cuda{}, dv.data(), dv.data(), values.size());
    EXPECT_EQ(exec::transfers().scalars, read_before) << "a queued scan reads nothing back";
    exec::exclusive_scan(exec::Host{}, values.data(), values.data(), values.size());
    EXPECT_EQ(on_host(dv), values);
}

namespace {
struct Big {
    const double* v;
    EMERGENT_HD bool operator()(std::size_t i) const { return fabs(v[i]) > 1e5; }
};
}  // namespace

TEST(CudaExecution, FirstIndexAgreesWithHost) {
    SKIP_WITHOUT_DEVICE();
    gpu::select_device();
    const auto v = fixtures::spread_values(1000003, 15);
    auto d = on_device(v);
    const std::size_t host = exec::first_index(exec::Host{}, v.size(), Big{v.data()});
    ASSERT_LT(host, v.size());
    EXPECT_EQ(exec::first_index(exec::Cuda{}, v.size(), Big{d.data()}), host);
    auto none = on_device(std::vector<double>(1000, 1.0));
    EXPECT_EQ(exec::first_index(exec::Cuda{}, 1000, Big{none.data()}), 1000u);
}

TEST(CudaExecution, SumIfAgreesWithHost) {
    SKIP_WITHOUT_DEVICE();
    gpu::select_device();
    const auto v = fixtures::spread_values(1000003, 16);
    auto d = on_device(v);
    const double host = exec::transform_sum_if(exec::Host{}, v.size(), 12.5, Big{v.data()}, Read{v.data()});
    const double device = exec::transform_sum_if(exec::Cuda{}, v.size(), 12.5, Big{d.data()}, Read{d.data()});
    double magnitude = 12.5;
    for (double x : v) magnitude += fabs(x) > 1e5 ? fabs(x) : 0;
    EXPECT_LE(fabs(device - host), v.size() * std::numeric_limits<double>::epsilon() * magnitude);
}

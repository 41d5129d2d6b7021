// SPDX-License-Identifier: MIT
// The execution layer's host primitives against plain loops and the standard library written
// out here; their CUDA versions are compared with these in gpu_tests.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include "emergent/device_profile.hpp"
#include "emergent/execution.hpp"
#include "support/execution_cases.hpp"

using namespace emergent;

TEST(Execution, SumIsThePlainLoopBitwise) {
    const auto v = fixtures::spread_values(100001, 3);
    double loop = 0;
    for (double x : v) loop += x;
    const double sum = exec::transform_sum<double>(exec::Host{}, v.size(), [&](std::size_t i) { return v[i]; });
    EXPECT_EQ(sum, loop);  // bitwise: the engine's host sums keep their order
    EXPECT_EQ(exec::transform_sum<double>(exec::Host{}, 0, [&](std::size_t i) { return v[i]; }), 0.0);
}

TEST(Execution, MaxKeepsInitAndNan) {
    const auto v = fixtures::spread_values(5000, 4);
    const auto f = [&](std::size_t i) { return v[i]; };
    EXPECT_EQ(exec::transform_max(exec::Host{}, v.size(), -1e300, f), *std::max_element(v.begin(), v.end()));
    EXPECT_EQ(exec::transform_max(exec::Host{}, 0, -7.0, f), -7.0);
    EXPECT_EQ(exec::transform_max(exec::Host{}, v.size(), 1e300, f), 1e300);
    auto w = v;
    w[1234] = std::numeric_limits<double>::quiet_NaN();
    // A NaN must win wherever it is, also against larger values after it: a guard reads it.
    EXPECT_TRUE(std::isnan(exec::transform_max(exec::Host{}, w.size(), 0.0, [&](std::size_t i) { return w[i]; })));
    EXPECT_TRUE(std::isnan(exec::max_keeping_nan(1.0, std::nan(""))));
    EXPECT_TRUE(std::isnan(exec::max_keeping_nan(std::nan(""), 1.0)));
}

namespace {
struct Double {
    double* a;
    void operator()(std::size_t i) const { a[i] *= 2; }
};
struct Element {
    const double* a;
    double operator()(std::size_t i) const { return a[i]; }
};
}  // namespace

TEST(Execution, StageThenMeasureActsOnEveryParticle) {
    // A stage fused with the reduction over its result acts on every particle, also past a
    // NaN (the step's state stays whole for the failure report), and the reduction sees what
    // the stage left.
    auto v = fixtures::spread_values(5000, 5);
    v[100] = std::numeric_limits<double>::quiet_NaN();
    auto expected = v;
    for (double& x : expected) x *= 2;
    const exec::Then<Double, Element> stage{{v.data()}, {v.data()}};
    EXPECT_TRUE(std::isnan(exec::transform_max(exec::Host{}, v.size(), 0.0, stage)));
    for (std::size_t i = 0; i < v.size(); ++i)
        if (i != 100) ASSERT_EQ(v[i], expected[i]) << i;
    v[100] = 1;
    double sum = 0;
    for (double x : v) sum += 2 * x;
    EXPECT_EQ(exec::transform_sum<double>(exec::Host{}, v.size(), stage), sum);
}

TEST(Execution, ExclusiveScanInPlaceAndTotal) {
    std::vector<std::uint32_t> keys, values;
    fixtures::repeated_keys(777, 6, 5, keys, values);
    std::vector<std::uint32_t> expected(keys.size());
    std::uint32_t running = 0;
    for (std::size_t i = 0; i < keys.size(); ++i) {
        expected[i] = running;
        running += keys[i];
    }
    std::vector<std::uint32_t> out(keys.size());
    EXPECT_EQ(exec::exclusive_scan(exec::Host{}, keys.data(), out.data(), keys.size()), running);
    EXPECT_EQ(out, expected);
    EXPECT_EQ(exec::exclusive_scan(exec::Host{}, keys.data(), keys.data(), keys.size()), running);
    EXPECT_EQ(keys, expected);
    EXPECT_EQ(exec::exclusive_scan(exec::Host{}, keys.data(), keys.data(), 0), 0u);
}

TEST(Execution, SortPairsIsStable) {
    std::vector<std::uint32_t> keys, values;
    fixtures::repeated_keys(20000, 8, 6, keys, values);  // ~80 of each key
    std::vector<std::pair<std::uint32_t, std::uint32_t>> reference;
    for (std::size_t i = 0; i < keys.size(); ++i) reference.push_back({keys[i], values[i]});
    // Values are the original positions, so sorting pairs fully gives the stable order.
    std::sort(reference.begin(), reference.end());
    exec::sort_pairs(exec::Host{}, keys.data(), values.data(), keys.size(), 8);
    for (std::size_t i = 0; i < keys.size(); ++i) {
        ASSERT_EQ(keys[i], reference[i].first) << i;
        ASSERT_EQ(values[i], reference[i].second) << i;
    }
}

TEST(Execution, SortPairsOfWideKeysOrdersByCellThenId) {
    // A list build's one sort: 64-bit keys, a cell above an id. Against a plain stable sort of
    // (cell, id) pairs; the ids are distinct, so the order is the only one.
    std::vector<std::uint64_t> keys;
    std::vector<std::uint32_t> values;
    fixtures::cell_and_id_keys(20000, 9, 5, keys, values);
    std::vector<std::pair<std::uint64_t, std::uint32_t>> reference;
    for (std::size_t i = 0; i < keys.size(); ++i) reference.push_back({keys[i], values[i]});
    std::stable_sort(reference.begin(), reference.end(), [](const auto& a, const auto& b) {
        const std::uint64_t ca = a.first >> 32, cb = b.first >> 32;
        return ca != cb ? ca < cb : (a.first & 0xffffffffu) < (b.first & 0xffffffffu);
    });
    exec::sort_pairs(exec::Host{}, keys.data(), values.data(), keys.size(), 32 + 9);
    for (std::size_t i = 0; i < keys.size(); ++i) {
        ASSERT_EQ(keys[i], reference[i].first) << i;
        ASSERT_EQ(values[i], reference[i].second) << i;
    }
    // A cell beyond the bits said is refused, as for 32-bit keys.
    std::vector<std::uint64_t> wide{std::uint64_t{1} << 41, 1};
    std::vector<std::uint32_t> two{0, 1};
    EXPECT_THROW(exec::sort_pairs(exec::Host{}, wide.data(), two.data(), 2, 41), std::invalid_argument);
}

TEST(Execution, QueuedScanIsTheScanAndReadsNothingBack) {
    std::vector<std::uint32_t> keys, values;
    fixtures::repeated_keys(10001, 4, 3, keys, values);
    std::vector<std::uint32_t> expected(keys.size()), got = keys;
    exec::exclusive_scan(exec::Host{}, keys.data(), expected.data(), keys.size());
    const exec::Target checking{false, true, nullptr};
    const exec::Transfers before = exec::transfers();
    exec::exclusive_scan_queued(checking, got.data(), got.data(), got.size());
    EXPECT_EQ(got, expected);
    EXPECT_EQ(exec::transfers().scalars, before.scalars);
    EXPECT_EQ(exec::transfers().passes, before.passes + 1);
}

TEST(Execution, HostMovesNothing) {
    const exec::Transfers before = exec::transfers();
    const auto v = fixtures::spread_values(100, 7);
    exec::transform_sum<double>(exec::Host{}, v.size(), [&](std::size_t i) { return v[i]; });
    EXPECT_EQ(exec::transfers().scalars, before.scalars);
    EXPECT_EQ(exec::transfers().arrays, before.arrays);
}

TEST(Execution, FirstIndexFindsTheFirstOffender) {
    const auto v = fixtures::spread_values(10000, 8);
    const auto big = [&](std::size_t i) { return std::fabs(v[i]) > 1e5; };
    std::size_t expected = v.size();
    for (std::size_t i = 0; i < v.size(); ++i)
        if (big(i)) {
            expected = i;
            break;
        }
    ASSERT_LT(expected, v.size()) << "the case needs an offender";
    EXPECT_EQ(exec::first_index(exec::Host{}, v.size(), big), expected);
    EXPECT_EQ(exec::first_index(exec::Host{}, v.size(), [](std::size_t) { return false; }), v.size());
}

TEST(Execution, SumIfIsTheRunningTotalOfAPlainLoop) {
    const auto v = fixtures::spread_values(20000, 9);
    const auto few = [&](std::size_t i) { return v[i] > 1e4; };  // a few per cent of them
    double loop = 12.5;
    int picked = 0;
    for (std::size_t i = 0; i < v.size(); ++i)
        if (few(i)) loop += v[i], ++picked;
    ASSERT_GT(picked, 10);
    ASSERT_LT(picked, 2000);
    EXPECT_EQ(exec::transform_sum_if(exec::Host{}, v.size(), 12.5, few, [&](std::size_t i) { return v[i]; }), loop);
}

TEST(Execution, SortPairsRefusesKeysWiderThanSaid) {
    std::vector<std::uint32_t> keys{1, 300, 2}, values{0, 1, 2};
    // 300 needs 9 bits: on CUDA an 8-bit sort would ignore its top bit, so the host refuses it.
    EXPECT_THROW(exec::sort_pairs(exec::Host{}, keys.data(), values.data(), 3, 8), std::invalid_argument);
    EXPECT_NO_THROW(exec::sort_pairs(exec::Host{}, keys.data(), values.data(), 3, 9));
}

// The run-time target: its host forms are the host loops (a checking target counts each
// result read back, as a device would), and a loop compiled as plain C++ refuses the device
// with a message instead of running on the host behind the user's back.
TEST(Execution, TargetRunsTheHostLoopsAndCountsWhatADeviceReadsBack) {
    std::vector<double> a{1.5, -2.0, 4.25};
    const exec::ElementOf<double> element{a.data()};
    const exec::Target host, checking{false, true, nullptr};
    const exec::Transfers before = exec::transfers();
    EXPECT_EQ(exec::transform_sum<double>(host, a.size(), element), 3.75);
    EXPECT_EQ(exec::transfers().scalars, before.scalars);
    EXPECT_EQ(exec::transform_max(checking, a.size(), 0.0, element), 4.25);
    EXPECT_EQ(exec::read_one(checking, a.data() + 1), -2.0);
    EXPECT_EQ(exec::transfers().scalars, before.scalars + 2);
    EXPECT_EQ(exec::transfers().arrays, before.arrays);
}

TEST(Execution, TargetRefusesTheDeviceWhereCompiledWithoutCuda) {
    std::vector<double> a(4, 1.0);
    const exec::Target device{true, true, nullptr};
    try {
        exec::for_each(device, a.size(), exec::ElementOf<double>{a.data()});
        FAIL() << "a loop compiled without CUDA ran with a device target";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("compiled without CUDA"), std::string::npos) << e.what();
    }
}

// The device profile names a call by its functor, taken from the launcher's signature as GCC
// spells it (the form the CUDA back end passes), template arguments and all.
TEST(DeviceProfile, NamesEachCallByItsFunctorAndTalliesItsCalls) {
    exec::profile_add("loop", "const char* emergent::exec::functor_name() [with Functor = emergent::integrate::KickDrift]", 0.5);
    exec::profile_add("loop", "const char* emergent::exec::functor_name() [with Functor = emergent::integrate::KickDrift]", 0.25);
    exec::profile_add("reduce", "const char* emergent::exec::functor_name() [with Functor = emergent::{anonymous}::Pair<emergent::Vec3, 2>; std::size_t = long unsigned int]", 1.0);
    const std::string table = exec::profile_table();
    EXPECT_NE(table.find("loop  integrate::KickDrift\n"), std::string::npos) << table;
    EXPECT_NE(table.find("reduce  {anonymous}::Pair<Vec3, 2>\n"), std::string::npos) << table;
    // Longest total first; the KickDrift row shows 2 calls of 375 us each.
    EXPECT_LT(table.find("Pair<"), table.find("KickDrift")) << table;
    EXPECT_NE(table.find(" 2     375000.00  loop  integrate::KickDrift"), std::string::npos) << table;
}

// SPDX-License-Identifier: MIT
// random_sequential_packing: no two spheres overlap (against all pairs), every centre lies in
// the region where `inside` holds, the same seed gives the same packing, and a region too full
// is one clear error.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "emergent/error.hpp"
#include "emergent/kit/lattice.hpp"

using namespace emergent;

TEST(RandomPacking, NoOverlapsInsideTheRegionAndRepeatable) {
    std::vector<double> d;
    for (int i = 0; i < 600; ++i) d.push_back(i % 3 == 0 ? 1.45 : 0.95);
    const Vec3 lo{0, 0, 0}, hi{20, 10, 12};
    auto inside = [](const Vec3& x, double di) { return std::hypot(x.x - 10, x.y - 5) < 9 - di / 2; };
    const std::vector<Vec3> a = random_sequential_packing(lo, hi, d, 1.1, 42, inside);
    ASSERT_EQ(a.size(), d.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_TRUE(inside(a[i], d[i]));
        for (int k = 0; k < 3; ++k) EXPECT_TRUE(a[i][k] >= lo[k] && a[i][k] < hi[k]);
        for (std::size_t j = 0; j < i; ++j) {
            const Vec3 r = a[i] - a[j];
            ASSERT_GE(std::sqrt(dot(r, r)), 0.5 * 1.1 * (d[i] + d[j])) << i << " " << j;
        }
    }
    const std::vector<Vec3> b = random_sequential_packing(lo, hi, d, 1.1, 42, inside);
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].x, b[i].x);
    const std::vector<Vec3> c = random_sequential_packing(lo, hi, d, 1.1, 43, inside);
    EXPECT_NE(a[0].x, c[0].x);
}

TEST(RandomPacking, ARegionTooFullIsRefused) {
    const std::vector<double> d(50, 1.0);
    EXPECT_THROW(random_sequential_packing({0, 0, 0}, {2, 2, 2}, d, 1.0, 1,
                                           [](const Vec3&, double) { return true; }, 200),
                 InputError);
}

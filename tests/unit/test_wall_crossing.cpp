// SPDX-License-Identifier: MIT
// The boundary rules' per-step scan for particles beyond a wall: the same test as
// WallGeometry::on_fluid_side, for every wall kind, axis and side.
#include <gtest/gtest.h>

#include <vector>

#include "boundary/wall_geometry.hpp"
#include "emergent/random.hpp"

using namespace emergent;

TEST(WallCrossing, ScanFindsExactlyTheParticlesNotOnTheFluidSide) {
    // Random points in a box around the wall, plus points exactly on it (a wall puts the
    // particles it returns there, and the two tests must agree on them too).
    std::vector<Vec3> x;
    for (int i = 0; i < 4000; ++i)
        x.push_back({8 * uniform_open(5, i, 0) - 4, 8 * uniform_open(5, i, 1) - 4,
                     8 * uniform_open(5, i, 2) - 4});
    int checked = 0;
    for (const bool plane : {true, false})
        for (int axis = 0; axis < 3; ++axis)
            for (const int side : {+1, -1}) {
                const WallShape shape = plane ? WallShape::plane(axis, 0.7, side)
                                              : WallShape::cylinder(axis, {0.3, -0.2, 0.1}, 2.5, side);
                std::vector<Vec3> points = x;
                for (int k = 0; k < 50; ++k) {  // on the wall
                    Vec3 p = x[k];
                    if (plane) {
                        p[axis] = 0.7;
                    } else {
                        Vec3 r = p - shape.centre;
                        r[axis] = 0;
                        p = shape.centre + (2.5 / std::sqrt(dot(r, r))) * r;
                        p[axis] = x[k][axis];
                    }
                    points.push_back(p);
                }
                const boundary::WallGeometry wall{shape, {}};
                std::vector<std::size_t> expected, found;
                for (std::size_t i = 0; i < points.size(); ++i)
                    if (!wall.on_fluid_side(points[i])) expected.push_back(i);
                boundary::with_crossing_test(shape, [&](auto beyond) {
                    for (std::size_t i = 0; i < points.size(); ++i)
                        if (beyond(points[i])) found.push_back(i);
                });
                SCOPED_TRACE(std::string(plane ? "plane" : "cylinder") + " axis " +
                             std::to_string(axis) + " side " + std::to_string(side));
                EXPECT_EQ(found, expected);
                // Both sides are populated, so a scan that finds nothing (or all) fails.
                EXPECT_GT(expected.size(), 100u);
                EXPECT_LT(expected.size(), points.size() - 100);
                ++checked;
            }
    EXPECT_EQ(checked, 12);
}

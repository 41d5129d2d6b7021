// SPDX-License-Identifier: MIT
// Orthorhombic simulation region with per-axis periodicity, optionally cut to a wedge whose
// two faces are joined by a rotation about the z axis.
#pragma once

#include <cmath>

#include "emergent/vec3.hpp"

namespace emergent {

/// Rotational periodic images: the region is the wedge 0 <= theta < 2 pi / n about the z axis
/// (theta measured from +x towards +y), and what leaves through one cut face re-enters through
/// the other, coordinates and velocities rotated by 2 pi / n. n = 0 means no wedge.
struct Wedge {
    int n = 0;

    EMERGENT_HD bool active() const { return n > 0; }
    EMERGENT_HD Real angle() const { return 6.283185307179586 / n; }
    /// Rotation of a vector about z by `turns` wedge angles.
    EMERGENT_HD Vec3 rotate(const Vec3& v, int turns) const {
        const Real a = turns * angle();
        Real c = std::cos(a), s = std::sin(a);
        // Quarter turns are exact: cos(pi/2) is 6e-17 in floating point, not 0.
        if (std::fabs(c) < 1e-15) c = 0;
        if (std::fabs(s) < 1e-15) s = 0;
        return {c * v.x - s * v.y, s * v.x + c * v.y, v.z};
    }
    /// Distance of x from the cut face theta = 0 (the half-plane y = 0, x >= 0).
    EMERGENT_HD static Real distance_to_first_face(const Vec3& x) {
        return x.x >= 0 ? std::fabs(x.y) : std::sqrt(x.x * x.x + x.y * x.y);
    }
    /// Distance of x from the cut face theta = 2 pi / n.
    EMERGENT_HD Real distance_to_second_face(const Vec3& x) const {
        return distance_to_first_face(rotate(x, -1));
    }
    /// Wedge turns that bring x into the wedge (0 when it is inside).
    EMERGENT_HD int turns_into(const Vec3& x) const {
        Real theta = std::atan2(x.y, x.x);
        if (theta < 0) theta += 6.283185307179586;
        // Points within round-off of theta = 2 pi belong to the first face.
        const int k = static_cast<int>(std::floor(theta / angle()));
        return k >= n ? 0 : -k;
    }
};

/// Axis-aligned box [lo, hi) in each dimension; each axis is periodic or bounded.
struct Box {
    Vec3 lo{0, 0, 0};
    Vec3 hi{0, 0, 0};
    bool periodic[3] = {true, true, true};
    Wedge wedge;  ///< rotational images about z (x and y are then bounded and not split)

    EMERGENT_HD Vec3 length() const { return hi - lo; }
    /// x moved into [lo, hi) along the periodic axes (the image every rank agrees on).
    EMERGENT_HD Vec3 primary_image(Vec3 x) const {
        for (int d = 0; d < 3; ++d) {
            if (!periodic[d]) continue;
            const Real l = hi[d] - lo[d];
            x[d] -= l * std::floor((x[d] - lo[d]) / l);
            if (x[d] >= hi[d]) x[d] = lo[d];  // a hair below lo rounds up to hi
        }
        return x;
    }
    EMERGENT_HD Real volume() const {
        const Vec3 l = length();
        return l.x * l.y * l.z;
    }
};

/// A fluid layer between walls at z = 0 and z = height, periodic in x and y. The box reaches
/// `margin` past each wall, so a particle resting on a wall is still inside it.
inline Box wall_bounded_layer(Real lx, Real ly, Real height, Real margin = 0.5) {
    Box box;
    box.lo = {0, 0, -margin};
    box.hi = {lx, ly, height + margin};
    box.periodic[2] = false;
    return box;
}

}  // namespace emergent

// SPDX-License-Identifier: MIT
// Three-component vector used for positions, velocities and forces on host and device.
#pragma once

#include "emergent/macros.hpp"

namespace emergent {

/// Floating-point type of the reference (double-precision) path.
using Real = double;

/// A 3-vector; plain aggregate so arrays of it are trivially copyable and device-friendly.
struct Vec3 {
    Real x, y, z;

    EMERGENT_HD Real& operator[](int d) { return d == 0 ? x : (d == 1 ? y : z); }
    EMERGENT_HD Real operator[](int d) const { return d == 0 ? x : (d == 1 ? y : z); }
    EMERGENT_HD Vec3& operator+=(const Vec3& o) { x += o.x; y += o.y; z += o.z; return *this; }
    EMERGENT_HD Vec3& operator-=(const Vec3& o) { x -= o.x; y -= o.y; z -= o.z; return *this; }
    EMERGENT_HD Vec3& operator*=(Real s) { x *= s; y *= s; z *= s; return *this; }
};

EMERGENT_HD inline Vec3 operator+(Vec3 a, const Vec3& b) { return a += b; }
EMERGENT_HD inline Vec3 operator-(Vec3 a, const Vec3& b) { return a -= b; }
EMERGENT_HD inline Vec3 operator*(Real s, Vec3 a) { return a *= s; }
EMERGENT_HD inline Vec3 operator*(Vec3 a, Real s) { return a *= s; }
EMERGENT_HD inline Real dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
EMERGENT_HD inline Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

/// Integer 3-vector: periodic image counts, cell coordinates, rank-grid coordinates.
struct Int3 {
    int x, y, z;
    EMERGENT_HD int& operator[](int d) { return d == 0 ? x : (d == 1 ? y : z); }
    EMERGENT_HD int operator[](int d) const { return d == 0 ? x : (d == 1 ? y : z); }
};

}  // namespace emergent

// SPDX-License-Identifier: MIT
// Unit quaternions for rigid-body orientation (host and device).
#pragma once

#include <cmath>

#include "emergent/vec3.hpp"

namespace emergent {

/// q = w + x i + y j + z k. An orientation maps body-frame vectors to the space frame.
struct Quat {
    Real w = 1, x = 0, y = 0, z = 0;

    EMERGENT_HD Real operator[](int k) const { return k == 0 ? w : (k == 1 ? x : (k == 2 ? y : z)); }
};

EMERGENT_HD inline Quat operator*(const Quat& a, const Quat& b) {
    return {a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z, a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
            a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x, a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}
EMERGENT_HD inline Quat operator*(Real s, const Quat& q) { return {s * q.w, s * q.x, s * q.y, s * q.z}; }
EMERGENT_HD inline Quat operator+(const Quat& a, const Quat& b) {
    return {a.w + b.w, a.x + b.x, a.y + b.y, a.z + b.z};
}
EMERGENT_HD inline Quat conjugate(const Quat& q) { return {q.w, -q.x, -q.y, -q.z}; }
EMERGENT_HD inline Real dot(const Quat& a, const Quat& b) {
    return a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z;
}
EMERGENT_HD inline Quat normalized(const Quat& q) {
    const Real n = std::sqrt(dot(q, q));
    return {q.w / n, q.x / n, q.y / n, q.z / n};
}
/// The vector v rotated by the unit quaternion q (body frame -> space frame).
EMERGENT_HD inline Vec3 rotate(const Quat& q, const Vec3& v) {
    const Quat r = q * Quat{0, v.x, v.y, v.z} * conjugate(q);
    return {r.x, r.y, r.z};
}
/// The vector v rotated by the inverse of q (space frame -> body frame).
EMERGENT_HD inline Vec3 rotate_back(const Quat& q, const Vec3& v) { return rotate(conjugate(q), v); }

}  // namespace emergent

// SPDX-License-Identifier: MIT
// Rotational dynamics of rigid bodies by the NO_SQUISH splitting (Miller, Eleftheriou, Pattnaik,
// Ndirango, Newns and Martyna, J. Chem. Phys. 116, 8649 (2002)), as used by LAMMPS and HOOMD.
//
// Why this method: it is symplectic and time-reversible, keeps the quaternion normalised
// without projection, and each sub-step is the exact flow of a free rotation about one
// principal axis, so the space-frame angular momentum of a torque-free body is conserved to
// round-off and its energy error stays bounded (no drift).
#pragma once

#include "emergent/quaternion.hpp"

namespace emergent::rigid {

/// Orientation q and its conjugate momentum p (a quaternion), principal moments I (body frame).
struct Rotor {
    Quat q;
    Quat p{0, 0, 0, 0};
    Vec3 inertia{1, 1, 1};
};

/// P_k q: the permutations of NO_SQUISH (k = 1, 2, 3).
EMERGENT_HD inline Quat permute(int k, const Quat& q) {
    if (k == 1) return {-q.x, q.w, q.z, -q.y};
    if (k == 2) return {-q.y, -q.z, q.w, q.x};
    return {-q.z, q.y, -q.x, q.w};
}

/// Exact free rotation about principal axis k for a time dt.
EMERGENT_HD inline void free_rotation(Rotor& r, int k, Real dt) {
    const Real moment = k == 1 ? r.inertia.x : (k == 2 ? r.inertia.y : r.inertia.z);
    if (!(moment > 0)) return;  // a linear or point body has no rotation about this axis
    const Quat pq = permute(k, r.q), pp = permute(k, r.p);
    const Real zeta = dt * dot(r.p, pq) / (4 * moment);
    const Real c = std::cos(zeta), s = std::sin(zeta);
    r.q = c * r.q + s * pq;
    r.p = c * r.p + s * pp;
}

/// The symmetric splitting R3(dt/2) R2(dt/2) R1(dt) R2(dt/2) R3(dt/2).
EMERGENT_HD inline void rotate_freely(Rotor& r, Real dt) {
    free_rotation(r, 3, 0.5 * dt);
    free_rotation(r, 2, 0.5 * dt);
    free_rotation(r, 1, dt);
    free_rotation(r, 2, 0.5 * dt);
    free_rotation(r, 3, 0.5 * dt);
}

/// Half kick by a space-frame torque: p += dt q (0, tau_body) (= 2 (dt/2) S(q) tau).
EMERGENT_HD inline void torque_kick(Rotor& r, const Vec3& torque_space, Real half_dt) {
    const Vec3 tb = rotate_back(r.q, torque_space);
    r.p = r.p + (2 * half_dt) * (r.q * Quat{0, tb.x, tb.y, tb.z});
}

/// Body-frame angular momentum: the vector part of q* p / 2.
EMERGENT_HD inline Vec3 body_angular_momentum(const Rotor& r) {
    const Quat l = conjugate(r.q) * r.p;
    return {0.5 * l.x, 0.5 * l.y, 0.5 * l.z};
}

/// Sets p from a body-frame angular velocity.
EMERGENT_HD inline void set_angular_velocity(Rotor& r, const Vec3& omega_body) {
    r.p = 2.0 * (r.q * Quat{0, r.inertia.x * omega_body.x, r.inertia.y * omega_body.y,
                            r.inertia.z * omega_body.z});
}

/// Body-frame angular velocity (zero about axes with zero moment).
EMERGENT_HD inline Vec3 angular_velocity_body(const Rotor& r) {
    const Vec3 l = body_angular_momentum(r);
    return {r.inertia.x > 0 ? l.x / r.inertia.x : 0, r.inertia.y > 0 ? l.y / r.inertia.y : 0,
            r.inertia.z > 0 ? l.z / r.inertia.z : 0};
}

EMERGENT_HD inline Real rotational_energy(const Rotor& r) {
    const Vec3 l = body_angular_momentum(r), w = angular_velocity_body(r);
    return 0.5 * dot(l, w);
}

}  // namespace emergent::rigid

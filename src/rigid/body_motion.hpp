// SPDX-License-Identifier: MIT
// The rigid bodies' passes as per-body functors for the execution layer (the same code on CPU
// and GPU): kicks and drifts by NO_SQUISH with their constituents placed after, the force and
// torque on each body from its constituents, and the bodies' sums (kinetic energy, momenta).
// A body writes only its own constituents, so bodies run in parallel.
#pragma once

#include <cstdint>

#include "emergent/random.hpp"
#include "rigid/no_squish.hpp"

namespace emergent::rigid {

/// The body kinds' principal frames as flat arrays: mass, principal moments, and the
/// constituent positions of kind k at positions[first[k] .. first[k + 1]).
struct FrameTable {
    const double* mass;
    const Vec3* inertia;
    const std::uint32_t* first;
    const Vec3* positions;
};

/// The owned bodies' state (a body store with rigid fields; species = kind).
struct BodyState {
    Vec3* x;
    Vec3* v;
    Vec3* force;
    Quat* q;
    Quat* p;
    Vec3* torque;
    const int* kind;
};

/// Where each body's constituents sit among the particles: index[first[b] .. first[b + 1]).
struct ConstituentIndex {
    const std::uint32_t* first;
    const std::uint32_t* index;
};

/// The rotation of q as a matrix, q v q* for any q (not only unit ones): a body's many arms
/// turned at 15 flops each instead of the quaternion product's 56.
struct RotationMatrix {
    Real m[3][3];
    EMERGENT_HD explicit RotationMatrix(const Quat& q) {
        const Real ww = q.w * q.w, xx = q.x * q.x, yy = q.y * q.y, zz = q.z * q.z;
        const Real xy = q.x * q.y, xz = q.x * q.z, yz = q.y * q.z, wx = q.w * q.x, wy = q.w * q.y,
                   wz = q.w * q.z;
        m[0][0] = ww + xx - yy - zz, m[0][1] = 2 * (xy - wz), m[0][2] = 2 * (xz + wy);
        m[1][0] = 2 * (xy + wz), m[1][1] = ww - xx + yy - zz, m[1][2] = 2 * (yz - wx);
        m[2][0] = 2 * (xz - wy), m[2][1] = 2 * (yz + wx), m[2][2] = ww - xx - yy + zz;
    }
    EMERGENT_HD Vec3 operator()(const Vec3& v) const {
        return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
    }
};

/// Puts body b's constituents where its state says (positions unless velocities_only) with
/// their velocities V + omega x arm.
EMERGENT_HD inline void place_constituents(const BodyState& s, const FrameTable& frames,
                                           const ConstituentIndex& c, std::size_t b, Vec3* x,
                                           Vec3* v, bool velocities_only) {
    const int k = s.kind[b];
    const Rotor r{s.q[b], s.p[b], frames.inertia[k]};
    const Vec3 w = rotate(r.q, angular_velocity_body(r));
    const Vec3 R = s.x[b], V = s.v[b];
    const RotationMatrix turn(s.q[b]);
    for (std::uint32_t j = 0; j < frames.first[k + 1] - frames.first[k]; ++j) {
        const std::uint32_t i = c.index[c.first[b] + j];
        const Vec3 arm = turn(frames.positions[frames.first[k] + j]);
        if (!velocities_only) x[i] = R + arm;
        v[i] = V + cross(w, arm);
    }
}

/// Momentum and angular momentum kicked by `kick`, then translation and free rotation by
/// `drift`, then the constituents placed.
struct BodyKickDrift {
    BodyState s;
    FrameTable frames;
    ConstituentIndex c;
    Vec3* x;
    Vec3* v;
    double kick, drift;

    EMERGENT_HD void operator()(std::size_t b) const {
        const int k = s.kind[b];
        s.v[b] += (kick / frames.mass[k]) * s.force[b];
        s.x[b] += drift * s.v[b];
        Rotor r{s.q[b], s.p[b], frames.inertia[k]};
        torque_kick(r, s.torque[b], kick);
        rotate_freely(r, drift);
        s.q[b] = r.q;
        s.p[b] = r.p;
        place_constituents(s, frames, c, b, x, v, false);
    }
};

/// Momentum and angular momentum kicked, constituent velocities set (unless `place` is false:
/// a pass that sets them anyway follows before anything reads them).
struct BodyKick {
    BodyState s;
    FrameTable frames;
    ConstituentIndex c;
    Vec3* x;
    Vec3* v;
    double kick;
    bool place = true;

    EMERGENT_HD void operator()(std::size_t b) const {
        const int k = s.kind[b];
        s.v[b] += (kick / frames.mass[k]) * s.force[b];
        Rotor r{s.q[b], s.p[b], frames.inertia[k]};
        torque_kick(r, s.torque[b], kick);
        s.p[b] = r.p;
        if (place) place_constituents(s, frames, c, b, x, v, true);
    }
};

/// Langevin dynamics of body b over one step (an implicit solvent), the exact
/// Ornstein-Uhlenbeck update: momentum relaxes by `decay_t` = exp(-gamma_t dt) and the angular
/// momentum about each principal axis by `decay_r`, each with the noise that keeps the
/// Maxwell distribution at `temperature`. Noise from (seed, body id, step): the same on any
/// rank count. Constituents' velocities follow.
struct BodyLangevin {
    BodyState s;
    FrameTable frames;
    ConstituentIndex c;
    const std::int64_t* id;
    Vec3* x;
    Vec3* v;
    double decay_t, decay_r, temperature;
    std::uint64_t seed;
    std::uint64_t step;

    EMERGENT_HD void operator()(std::size_t b) const {
        const int k = s.kind[b];
        const double m = frames.mass[k];
        const auto body = static_cast<std::uint64_t>(id[b]);
        const double kick_t = sqrt((1 - decay_t * decay_t) * temperature / m);
        for (int d = 0; d < 3; ++d)
            s.v[b][d] = decay_t * s.v[b][d] + kick_t * gaussian(seed, body, 6 * step + d);
        Rotor r{s.q[b], s.p[b], frames.inertia[k]};
        Vec3 w = angular_velocity_body(r);
        for (int d = 0; d < 3; ++d) {
            const double inertia = frames.inertia[k][d];
            const double kick_r = sqrt((1 - decay_r * decay_r) * temperature / inertia);
            w[d] = decay_r * w[d] + kick_r * gaussian(seed, body, 6 * step + 3 + d);
        }
        set_angular_velocity(r, w);
        s.p[b] = r.p;
        place_constituents(s, frames, c, b, x, v, true);
    }
};

/// Force and torque (about the centre of mass) on body b: its constituents' forces.
struct BodyForceAndTorque {
    BodyState s;
    ConstituentIndex c;
    const Vec3* x;
    const Vec3* f;

    EMERGENT_HD void operator()(std::size_t b) const {
        Vec3 F{0, 0, 0}, T{0, 0, 0};
        for (std::uint32_t k = c.first[b]; k < c.first[b + 1]; ++k) {
            const std::uint32_t i = c.index[k];
            F += f[i];
            T += cross(x[i] - s.x[b], f[i]);
        }
        s.force[b] = F;
        s.torque[b] = T;
    }
};

/// Body b's translational (x) and rotational (y) kinetic energy.
struct BodyKineticParts {
    BodyState s;
    FrameTable frames;
    EMERGENT_HD Vec3 operator()(std::size_t b) const {
        const int k = s.kind[b];
        const Rotor r{s.q[b], s.p[b], frames.inertia[k]};
        return {0.5 * frames.mass[k] * dot(s.v[b], s.v[b]), rotational_energy(r), 0.0};
    }
};

/// Body b's kinetic energy, translation plus rotation.
struct BodyKinetic {
    BodyKineticParts parts;
    EMERGENT_HD double operator()(std::size_t b) const {
        const Vec3 e = parts(b);
        return e.x + e.y;
    }
};

/// Body b's momentum.
struct BodyMomentum {
    BodyState s;
    FrameTable frames;
    EMERGENT_HD Vec3 operator()(std::size_t b) const { return frames.mass[s.kind[b]] * s.v[b]; }
};

/// Body b's angular momentum about the origin (its centre unwrapped by its image counts).
struct BodyAngularMomentum {
    BodyState s;
    FrameTable frames;
    const Int3* image;
    Vec3 box;
    EMERGENT_HD Vec3 operator()(std::size_t b) const {
        const int k = s.kind[b];
        const Int3 n = image[b];
        const Vec3 R = s.x[b] + Vec3{n.x * box.x, n.y * box.y, n.z * box.z};
        const Rotor r{s.q[b], s.p[b], frames.inertia[k]};
        return frames.mass[k] * cross(R, s.v[b]) + rotate(r.q, body_angular_momentum(r));
    }
};

}  // namespace emergent::rigid

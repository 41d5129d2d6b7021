// SPDX-License-Identifier: MIT
// Where a straight path meets a wall, and the wall's normal and velocity there.
#pragma once

#include <cmath>

#include "emergent/boundary.hpp"
#include "emergent/macros.hpp"

namespace emergent::boundary {

/// Geometry of one wall, with the operations a boundary rule needs (host and device).
struct WallGeometry {
    WallShape shape;
    WallMotion motion;

    /// Component of x perpendicular to a cylinder's axis, relative to its centre.
    EMERGENT_HD Vec3 radial(const Vec3& x) const {
        Vec3 r = x - shape.centre;
        r[shape.axis] = 0;
        return r;
    }

    /// True when x is on the particles' side of the wall (or on it).
    EMERGENT_HD bool on_fluid_side(const Vec3& x) const {
        if (shape.kind == WallShape::Kind::Plane)
            return shape.side * (x[shape.axis] - shape.position) >= 0;
        const Vec3 r = radial(x);
        const double rho2 = dot(r, r), r2 = shape.radius * shape.radius;
        return shape.side > 0 ? rho2 >= r2 : rho2 <= r2;
    }

    /// Signed distance from the wall, positive on the particles' side.
    EMERGENT_HD double gap(const Vec3& x) const {
        if (shape.kind == WallShape::Kind::Plane) return shape.side * (x[shape.axis] - shape.position);
        const Vec3 r = radial(x);
        return shape.side * (std::sqrt(dot(r, r)) - shape.radius);
    }

    /// Unit normal pointing into the particles' side, at a point on (or near) the wall.
    EMERGENT_HD Vec3 normal(const Vec3& x) const {
        Vec3 n{0, 0, 0};
        if (shape.kind == WallShape::Kind::Plane) {
            n[shape.axis] = shape.side;
            return n;
        }
        const Vec3 r = radial(x);
        return (shape.side / std::sqrt(dot(r, r))) * r;
    }

    /// Velocity of the wall's surface at x at time t.
    EMERGENT_HD Vec3 velocity_at(const Vec3& x, double t) const {
        const double f = motion.factor(t);
        if (motion.omega == 0) return f * motion.velocity;
        Vec3 axis{0, 0, 0};
        axis[shape.axis] = 1;
        return f * (motion.velocity + motion.omega * cross(axis, radial(x)));
    }

    /// Lever arm of x for angular momentum about the wall's axis through its centre (planes:
    /// the z axis through the centre).
    EMERGENT_HD double angular_component(const Vec3& x, const Vec3& dp) const {
        const int a = shape.kind == WallShape::Kind::Plane ? 2 : shape.axis;
        const Vec3 r = x - shape.centre;
        return cross(r, dp)[a];
    }

    /// Time in [0, dt] at which the path start + v t, which ends beyond the wall at t = dt,
    /// reaches it.
    EMERGENT_HD double impact_time(const Vec3& start, const Vec3& v, double dt) const {
        double t;
        if (shape.kind == WallShape::Kind::Plane) {
            const double g0 = gap(start), rate = shape.side * v[shape.axis];
            t = rate < 0 ? g0 / -rate : 0;
        } else {
            // |a + b t| = R: A t^2 + 2 B t + C = 0.
            const Vec3 a = radial(start), b = radial(v);
            const double A = dot(b, b), B = dot(a, b), C = dot(a, a) - shape.radius * shape.radius;
            const double disc = B * B - A * C;
            if (!(A > 0) || disc < 0) {
                t = 0;
            } else if (shape.side > 0) {
                // From outside inwards: the first root, written to avoid cancellation.
                const double q = -B + std::sqrt(disc);
                t = q > 0 ? C / q : 0;
            } else {
                // From inside outwards: the positive root (-B + sqrt(disc)) / A, written to
                // avoid cancellation.
                const double q = B + std::sqrt(disc);
                t = q > 0 ? -C / q : 0;
            }
        }
        if (!(t >= 0)) t = 0;
        return t > dt ? dt : t;
    }
};

}  // namespace emergent::boundary

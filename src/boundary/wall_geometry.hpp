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

/// The per-step test "is x beyond the wall" (not on its fluid side), written out per wall kind
/// and axis with the wall's numbers in registers: every particle is tested at every step and
/// few cross. It is WallGeometry::on_fluid_side's test, negated (tested against it for every
/// kind, axis and side).
template <int Axis>
struct BeyondPlane {
    double side, at;
    EMERGENT_HD bool operator()(const Vec3& p) const { return !(side * (p[Axis] - at) >= 0); }
};

/// Radial distance squared from the axis, summed in the order dot() sums it (0 for the axis).
template <int Axis>
EMERGENT_HD inline double radial_sq(const Vec3& r) {
    if (Axis == 0) return 0.0 * 0.0 + r.y * r.y + r.z * r.z;
    if (Axis == 1) return r.x * r.x + 0.0 * 0.0 + r.z * r.z;
    return r.x * r.x + r.y * r.y + 0.0 * 0.0;
}

/// Beyond a cylinder whose fluid lies outside (Outside) or inside it.
template <int Axis, bool Outside>
struct BeyondCylinder {
    Vec3 centre;
    double r2;
    EMERGENT_HD bool operator()(const Vec3& p) const {
        const double q = radial_sq<Axis>(p - centre);
        return Outside ? !(q >= r2) : !(q <= r2);
    }
};

/// Calls visit(beyond) with the test for this wall: the one place the wall's kind, axis and
/// side become a type.
template <class Visit>
void with_crossing_test(const WallShape& shape, Visit&& visit) {
    const bool plane = shape.kind == WallShape::Kind::Plane;
    const double r2 = shape.radius * shape.radius;
    const bool outside = shape.side > 0;
    const double side = shape.side;
    switch (shape.axis) {
    case 0:
        if (plane) return visit(BeyondPlane<0>{side, shape.position});
        return outside ? visit(BeyondCylinder<0, true>{shape.centre, r2})
                       : visit(BeyondCylinder<0, false>{shape.centre, r2});
    case 1:
        if (plane) return visit(BeyondPlane<1>{side, shape.position});
        return outside ? visit(BeyondCylinder<1, true>{shape.centre, r2})
                       : visit(BeyondCylinder<1, false>{shape.centre, r2});
    default:
        if (plane) return visit(BeyondPlane<2>{side, shape.position});
        return outside ? visit(BeyondCylinder<2, true>{shape.centre, r2})
                       : visit(BeyondCylinder<2, false>{shape.centre, r2});
    }
}

}  // namespace emergent::boundary

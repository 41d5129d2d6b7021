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

/// Calls cross(i) for each particle i in [0, n) beyond the wall (not on its fluid side). Every
/// particle is tested at every step and few cross, so the test is written out per wall kind
/// and axis with the wall's numbers in registers; it is
/// WallGeometry::on_fluid_side's test (host loop; tested against it for every kind, axis, side).
template <class Cross>
void for_each_crossing(const WallShape& shape, const Vec3* x, std::size_t n, Cross&& cross) {
    const double side = shape.side;
    auto scan = [&](auto beyond) {
        for (std::size_t i = 0; i < n; ++i)
            if (beyond(x[i])) cross(i);
    };
    auto plane = [&](auto coordinate) {
        const double at = shape.position;
        scan([=](const Vec3& p) { return !(side * (coordinate(p) - at) >= 0); });
    };
    // Radial distance squared from the axis, summed in the order dot() sums it.
    auto cylinder = [&](auto radial_sq) {
        const Vec3 c = shape.centre;
        const double r2 = shape.radius * shape.radius;
        if (shape.side > 0)
            scan([=](const Vec3& p) { return !(radial_sq(p - c) >= r2); });
        else
            scan([=](const Vec3& p) { return !(radial_sq(p - c) <= r2); });
    };
    const bool is_plane = shape.kind == WallShape::Kind::Plane;
    switch (shape.axis) {
    case 0:
        if (is_plane) return plane([](const Vec3& p) { return p.x; });
        return cylinder([](const Vec3& r) { return 0.0 * 0.0 + r.y * r.y + r.z * r.z; });
    case 1:
        if (is_plane) return plane([](const Vec3& p) { return p.y; });
        return cylinder([](const Vec3& r) { return r.x * r.x + 0.0 * 0.0 + r.z * r.z; });
    default:
        if (is_plane) return plane([](const Vec3& p) { return p.z; });
        return cylinder([](const Vec3& r) { return r.x * r.x + r.y * r.y + 0.0 * 0.0; });
    }
}

}  // namespace emergent::boundary

// SPDX-License-Identifier: MIT
// Grids on which particle data is coarse-grained: Cartesian boxes and cylindrical shells.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "emergent/vec3.hpp"

namespace emergent {

/// A grid of n[0] x n[1] x n[2] cells, either
///  - Cartesian: axes x, y, z over [lo, hi), or
///  - cylindrical about an axis through `lo` along `axis`: coordinates (r, theta, s) with r in
///    [r_min, r_max), theta in [theta_min, theta_max) (radians, measured from the next axis
///    in cyclic order: for axis z, from x towards y), s along the axis in [lo[axis], hi[axis]).
/// A dimension of 1 makes slabs (Cartesian) or rings/shells (cylindrical). This is the grid's
/// geometry, a value the back end's loops carry; FieldGrid adds its name.
struct FieldGeometry {
    enum class Kind { Cartesian, Cylindrical };

    Kind kind = Kind::Cartesian;
    Int3 n{1, 1, 1};
    Vec3 lo{0, 0, 0}, hi{1, 1, 1};
    int axis = 2;  ///< cylindrical only
    Real r_min = 0, r_max = 1, theta_min = 0, theta_max = 6.283185307179586;

    EMERGENT_HD int n_cells() const { return n.x * n.y * n.z; }

    /// Grid coordinates (x, y, z) or (r, theta, s) of a point.
    EMERGENT_HD Vec3 coordinates(const Vec3& p) const {
        if (kind == Kind::Cartesian) return p;
        const int a = axis, b = (axis + 1) % 3, c = (axis + 2) % 3;
        const Real u = p[b] - lo[b], v = p[c] - lo[c];
        Real theta = std::atan2(v, u);
        if (theta < theta_min) theta += 6.283185307179586;
        return {std::sqrt(u * u + v * v), theta, p[a]};
    }

    /// Components of vector v at point p along the grid's axes: (x, y, z), or (r, theta,
    /// axis) with the radial and azimuthal directions taken at p.
    EMERGENT_HD Vec3 components(const Vec3& p, const Vec3& v) const {
        if (kind == Kind::Cartesian) return v;
        const int a = axis, b = (axis + 1) % 3, c = (axis + 2) % 3;
        const Real u = p[b] - lo[b], w = p[c] - lo[c], rho = std::sqrt(u * u + w * w);
        if (!(rho > 0)) return {0, 0, v[a]};
        const Real cs = u / rho, sn = w / rho;
        return {cs * v[b] + sn * v[c], -sn * v[b] + cs * v[c], v[a]};
    }

    /// Linear cell index (x fastest) of a point, or -1 outside the grid.
    EMERGENT_HD int cell_of(const Vec3& p) const {
        if (kind == Kind::Cartesian) {
            // The axes in the order z, y, x: a thin horizontal slice (the commonest partial
            // grid) turns most points away after one test. Kept apart from the general branch
            // below on purpose: merged into one loop, g++ 12 stops inlining the field sampler
            // and a rayleigh-benard run takes 1.5 % more instructions (callgrind).
            int c[3];
            for (int d = 2; d >= 0; --d) {
                const Real f = (p[d] - lo[d]) / (hi[d] - lo[d]);
                if (!(f >= 0 && f < 1)) return -1;
                c[d] = static_cast<int>(f * n[d]);
                if (c[d] >= n[d]) c[d] = n[d] - 1;
            }
            return (c[2] * n.y + c[1]) * n.x + c[0];
        }
        const Vec3 q = coordinates(p);
        const Real lower[3] = {r_min, theta_min, lo[axis]};
        const Real upper[3] = {r_max, theta_max, hi[axis]};
        int c[3];
        for (int d = 0; d < 3; ++d) {
            const Real f = (q[d] - lower[d]) / (upper[d] - lower[d]);
            if (!(f >= 0 && f < 1)) return -1;
            c[d] = static_cast<int>(f * n[d]);
            if (c[d] >= n[d]) c[d] = n[d] - 1;
        }
        return (c[2] * n.y + c[1]) * n.x + c[0];
    }

};

/// A named grid (the name keys its frames in fields.h5 and checkpoints).
struct FieldGrid : FieldGeometry {
    std::string name = "box";

    /// Volume of cell k (cylindrical cells differ with r).
    Real cell_volume(int k) const {
        const int ix = k % n.x;
        if (kind == Kind::Cartesian) {
            const Vec3 l = hi - lo;
            return l.x * l.y * l.z / n_cells();
        }
        const Real dr = (r_max - r_min) / n.x, r0 = r_min + ix * dr, r1 = r0 + dr;
        const Real dtheta = (theta_max - theta_min) / n.y;
        const Real ds = (hi[axis] - lo[axis]) / n.z;
        return 0.5 * (r1 * r1 - r0 * r0) * dtheta * ds;
    }
};

/// Averages of one interval on one grid, as reduced over all ranks (identical on every rank).
struct FieldFrame {
    std::vector<double> density;  ///< particles per unit volume
    /// Mass-weighted mean flow, 3 per cell: (x, y, z) on Cartesian grids, (r, theta, axis) on
    /// cylindrical ones (components at each particle's own angle, so an azimuthal average of
    /// v_theta is the mean swirl, not a cancelling sum of x and y).
    std::vector<double> velocity;
    std::vector<double> temperature;  ///< from velocity fluctuations about the cell's mean flow
    std::vector<double> count;        ///< particle samples that fell in the cell
};

}  // namespace emergent

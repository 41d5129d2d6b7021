// SPDX-License-Identifier: MIT
// Mass, centre of mass and principal axes of a rigid set of spheres.
#pragma once

#include <vector>

#include "emergent/quaternion.hpp"

namespace emergent::rigid {

/// Constituent spheres of a body, in any frame.
struct BodyShape {
    std::vector<Vec3> positions;
    std::vector<double> masses, diameters;
};

/// The body in its principal frame: the centre of mass at the origin and the inertia tensor
/// diagonal. `orientation` maps this frame to the frame the shape was given in.
struct BodyFrame {
    double mass = 0;
    Vec3 inertia{0, 0, 0};           ///< principal moments, ascending
    std::vector<Vec3> positions;     ///< constituent positions in the principal frame
    Quat orientation;
    double extent = 0;               ///< largest distance of a sphere's surface from the centre
};

/// Constituents count as solid spheres (point mass plus (1/10) m d^2 about each axis).
BodyFrame principal_frame(const BodyShape& shape);

/// Eigen-decomposition of a symmetric 3x3 matrix (Jacobi rotations): eigenvalues ascending,
/// eigenvectors as the columns of `vectors` (a proper rotation).
void symmetric_eigen(const double a[3][3], double values[3], double vectors[3][3]);

}  // namespace emergent::rigid

// SPDX-License-Identifier: MIT
// The capsid model's particle (capsomer): a truncated pyramid of soft spheres with attraction
// sites on its lateral faces, shaped so that 60 of them tile a closed icosahedral shell.
#pragma once

#include <vector>

#include "emergent/quaternion.hpp"

namespace emergent {

/// One capsomer in the frame of a closed shell centred at the origin, as particle 0 of that
/// shell (particle k is icosahedral_rotations()[k] applied to it).
///
/// Design "PW": each face of an icosahedron of edge 3a is cut into three congruent trapezoids
/// (half regular hexagons, edges a, a, a, 2a); a capsomer is the truncated pyramid on one of
/// them with its apex at the shell's centre, so its lateral faces lie in planes through the
/// centre and the 60 bodies tile the shell. Its five contacts (the long base's two halves,
/// the short leg, the top, the leg) meet five neighbours (5-fold +-72 deg, 3-fold +-120 deg,
/// 2-fold 180 deg). Bond network: the pentagonal hexecontahedron's (150 bonds, 5 per particle).
struct Capsomer {
    double edge = 2.1;          ///< PW: the short edge a; PH: the long edge
    double face_distance = 0;   ///< distance of the outer face from the shell's centre
    /// The outer face's corners, V0 on a 5-fold axis (PW: the trapezoid V0..V3; PH: the
    /// pentagon V0..V4, V3 on a 3-fold axis).
    std::vector<Vec3> outer_face;
    /// Sphere centres (diameter 1): two layers, 0.5 and 1.2 below the outer face, each the
    /// boundary and interior of the layer's cross-section inset by `sphere_inset` from every
    /// lateral plane (spheres of bonded neighbours at least 2 sphere_inset apart).
    std::vector<Vec3> spheres;
    double sphere_inset = 0.57;
    /// Attraction sites: four per contact face, on the contact plane (so partners coincide in
    /// the closed shell), at the two layers' depths and two fractions along the contact.
    /// Site k has type k.
    std::vector<Vec3> sites;
    std::vector<int> partner;               ///< partner[k]: the one site type that k attracts
    std::vector<std::vector<int>> faces;    ///< the site types of each contact face
};

/// The PW capsomer with short edge `edge` (the paper's particles: edges 2.1 to 3.6).
Capsomer pw_capsomer(double edge = 2.1);

/// Design "PH": the same construction on a face of the pentagonal hexecontahedron (the dual
/// of the snub dodecahedron, found here from the group: the orbit point with five equal
/// nearest distances), with long edge `long_edge` (3.6: short edges 2.057; the paper quotes
/// edges of 2.1 to 3.6). Its bond network is PW's: both long edges are 5-fold contacts, the
/// two edges at the 3-fold corner 3-fold contacts, the fifth the 2-fold contact.
Capsomer ph_capsomer(double long_edge = 3.6);

/// The 60 rotations of the icosahedral group whose 5-fold axes pass through the vertices
/// s(0, +-1, +-phi) and cyclic permutations (the shell frame above): the identity first,
/// then in the order found from the generators (72 deg about the vertex (0, 1, phi), 120 deg
/// about (1, 1, 1)).
std::vector<Quat> icosahedral_rotations();

/// Rotation by `angle` (radians) about the unit vector `axis`.
Quat axis_angle(const Vec3& axis, double angle);

}  // namespace emergent

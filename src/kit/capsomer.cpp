// SPDX-License-Identifier: MIT
// The PW capsomer, constructed from the icosahedron (see emergent/kit/capsomer.hpp).
#include "emergent/kit/capsomer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace emergent {

namespace {

Vec3 unit(const Vec3& v) { return (1 / std::sqrt(dot(v, v))) * v; }
double norm(const Vec3& v) { return std::sqrt(dot(v, v)); }

/// The point p with dot(a, p) = ra, dot(b, p) = rb, dot(c, p) = rc (Cramer's rule).
Vec3 solve_planes(const Vec3& a, double ra, const Vec3& b, double rb, const Vec3& c, double rc) {
    const double det = dot(a, cross(b, c));
    return (1 / det) * (ra * cross(b, c) + rb * cross(c, a) + rc * cross(a, b));
}

/// One sign per rotation: q and -q are the same rotation.
Quat canonical(Quat q) {
    for (int k = 0; k < 4; ++k) {
        if (std::fabs(q[k]) < 1e-12) continue;
        return q[k] < 0 ? -1.0 * q : q;
    }
    return q;
}

bool same_rotation(const Quat& a, const Quat& b) { return std::fabs(std::fabs(dot(a, b)) - 1) < 1e-12; }

/// Sphere centres of one layer: the layer's cross-section (the outer face scaled towards the
/// centre), inset by `inset` from every lateral plane; its boundary at spacing <= 0.8 with
/// corners closer than 0.4 merged, then its interior filled at the point farthest from every
/// centre until no point of it is more than 0.55 from one (solvent cannot pass between).
std::vector<Vec3> sphere_layer(const std::vector<Vec3>& face, const Vec3& normal, double height,
                               const std::vector<Vec3>& inward, double inset) {
    const std::size_t n = face.size();
    std::vector<Vec3> corner(n);
    for (std::size_t k = 0; k < n; ++k)
        corner[k] = solve_planes(normal, height, inward[(k + n - 1) % n], inset, inward[k], inset);
    std::vector<Vec3> centres;
    for (std::size_t k = 0; k < n; ++k) {
        const Vec3 a = corner[k], b = corner[(k + 1) % n];
        const int segments = std::max(1, int(std::ceil(norm(b - a) / 0.8 - 1e-9)));
        for (int j = 0; j < segments; ++j) centres.push_back(a + (double(j) / segments) * (b - a));
    }
    for (bool merged = true; merged;) {
        merged = false;
        for (std::size_t i = 0; i < centres.size() && !merged; ++i)
            for (std::size_t j = i + 1; j < centres.size() && !merged; ++j)
                if (norm(centres[i] - centres[j]) < 0.4) {
                    centres[i] = 0.5 * (centres[i] + centres[j]);
                    centres.erase(centres.begin() + long(j));
                    merged = true;
                }
    }
    // Points of the inset section on a fine grid in its plane.
    const Vec3 e1 = unit(corner[1] - corner[0]), e2 = cross(normal, e1);
    double lo1 = 1e300, hi1 = -1e300, lo2 = 1e300, hi2 = -1e300;
    for (const Vec3& c : corner) {
        lo1 = std::min(lo1, dot(c - corner[0], e1)), hi1 = std::max(hi1, dot(c - corner[0], e1));
        lo2 = std::min(lo2, dot(c - corner[0], e2)), hi2 = std::max(hi2, dot(c - corner[0], e2));
    }
    std::vector<Vec3> samples;
    const double h = 0.01;
    for (double s = lo1; s <= hi1; s += h)
        for (double t = lo2; t <= hi2; t += h) {
            const Vec3 p = corner[0] + s * e1 + t * e2;
            bool inside = true;
            for (const Vec3& m : inward) inside = inside && dot(m, p) >= inset - 1e-12;
            if (inside) samples.push_back(p);
        }
    // Each sample's distance to its nearest centre, brought up to date as centres are added
    // (rescanning every centre per round grew as samples x centres^2: minutes at edge 10).
    std::vector<double> nearest(samples.size(), 1e300);
    for (std::size_t counted = 0;;) {
        for (; counted < centres.size(); ++counted)
            for (std::size_t i = 0; i < samples.size(); ++i)
                nearest[i] = std::min(nearest[i], norm(samples[i] - centres[counted]));
        double worst = 0;
        Vec3 at{0, 0, 0};
        for (std::size_t i = 0; i < samples.size(); ++i)
            if (nearest[i] > worst) worst = nearest[i], at = samples[i];
        if (worst <= 0.55) break;
        centres.push_back(at);
    }
    return centres;
}

}  // namespace

Quat axis_angle(const Vec3& axis, double angle) {
    const Vec3 u = unit(axis);
    const double s = std::sin(0.5 * angle);
    return {std::cos(0.5 * angle), s * u.x, s * u.y, s * u.z};
}

CageFrame cage_frame(int members) {
    const double phi = 0.5 * (1 + std::sqrt(5.0));
    switch (members) {
    case 12: return {{-1, 1, 1}, {1, -1, 1}, {1, 1, -1}, 3};
    case 24: return {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}, 4};
    case 60: return {{0, 1, phi}, {phi, 0, 1}, {1, phi, 0}, 5};
    default:
        throw std::invalid_argument("cage_frame: members=" + std::to_string(members) +
                                    " is not 12, 24 or 60");
    }
}

std::vector<Quat> cage_rotations(int members) {
    const CageFrame f = cage_frame(members);
    const double pi = std::acos(-1.0);
    // Every frame's face a, b, c is centred on the 3-fold axis (1, 1, 1).
    const Quat generators[2] = {axis_angle(f.a, 2 * pi / f.ring), axis_angle({1, 1, 1}, 2 * pi / 3)};
    std::vector<Quat> group{Quat{1, 0, 0, 0}};
    for (std::size_t next = 0; next < group.size(); ++next)
        for (const Quat& g : generators) {
            const Quat q = canonical(normalized(group[next] * g));
            if (std::none_of(group.begin(), group.end(), [&](const Quat& r) { return same_rotation(q, r); }))
                group.push_back(q);
        }
    if (int(group.size()) != members) throw std::logic_error("cage_rotations: closure has the wrong order");
    return group;
}

std::vector<Quat> icosahedral_rotations() { return cage_rotations(60); }

namespace {

/// A contact face: the segment of the outer face it stands on, from the end nearer the axis
/// relating the pair to the other end, and the two fractions along it at which sites sit.
struct Contact {
    Vec3 from, to;
    double u[2];
};

/// Spheres, sites and partners of a capsomer whose outer face and its distance from the centre
/// are set: the truncated pyramid on that face with its apex at the shell's centre. `outward`:
/// the face's unit normal.
void fill_capsomer(Capsomer& c, const Vec3& outward, const std::vector<Contact>& contacts) {
    const std::size_t n = c.outer_face.size();
    Vec3 middle{0, 0, 0};
    for (const Vec3& v : c.outer_face) middle += v;
    middle *= 1.0 / double(n);
    std::vector<Vec3> inward;  // lateral planes through the centre, one per edge V_k V_k+1
    for (std::size_t k = 0; k < n; ++k) {
        Vec3 m = unit(cross(c.outer_face[k], c.outer_face[(k + 1) % n]));
        inward.push_back(dot(m, middle) > 0 ? m : -1.0 * m);
    }
    const double depths[2] = {0.5, 1.2};
    for (const double d : depths) {
        const std::vector<Vec3> layer =
            sphere_layer(c.outer_face, outward, c.face_distance - d, inward, c.sphere_inset);
        c.spheres.insert(c.spheres.end(), layer.begin(), layer.end());
    }
    for (const Contact& k : contacts) {
        std::vector<int> face;
        for (const double d : {c.site_depths.outer, c.site_depths.inner})
            for (const double u : k.u) {
                face.push_back(int(c.sites.size()));
                c.sites.push_back(((c.face_distance - d) / c.face_distance) * (k.from + u * (k.to - k.from)));
            }
        c.faces.push_back(face);
    }
    // Partners from the closed shell: the site of another particle that coincides with each.
    const std::vector<Quat> group = icosahedral_rotations();
    c.partner.assign(c.sites.size(), -1);
    for (std::size_t a = 0; a < c.sites.size(); ++a)
        for (std::size_t g = 1; g < group.size(); ++g)
            for (std::size_t b = 0; b < c.sites.size(); ++b)
                if (norm(c.sites[a] - rotate(group[g], c.sites[b])) < 1e-9) {
                    if (c.partner[a] >= 0) throw std::logic_error("capsomer: a site meets two partners");
                    c.partner[a] = int(b);
                }
    for (std::size_t a = 0; a < c.sites.size(); ++a)
        if (c.partner[a] < 0 || c.partner[std::size_t(c.partner[a])] != int(a))
            throw std::logic_error("capsomer: site " + std::to_string(a) + " has no mutual partner");
}

/// How far the five nearest other points of the orbit of the unit vector along d lie from
/// their mean, relative to it: 0 for a vertex of the snub dodecahedron (five equal edges).
double edge_spread(const std::vector<Quat>& group, const Vec3& d) {
    const Vec3 v = unit(d);
    std::vector<double> r;
    for (std::size_t g = 1; g < group.size(); ++g) r.push_back(norm(rotate(group[g], v) - v));
    std::partial_sort(r.begin(), r.begin() + 5, r.end());
    return r[4] / r[0] - 1;
}

void check_site_depths(const SiteDepths& d) {
    if (!(d.outer >= 0 && d.outer < d.inner && d.inner <= 1.7))
        throw std::invalid_argument("capsomer: site depths " + std::to_string(d.outer) + ", " +
                                    std::to_string(d.inner) + " are not 0 <= outer < inner <= 1.7");
}

}  // namespace

Capsomer pw_capsomer(double edge, SiteDepths depths) {
    if (!(edge > 0)) throw std::invalid_argument("pw_capsomer: edge must be > 0");
    check_site_depths(depths);
    Capsomer c;
    c.edge = edge;
    c.site_depths = depths;
    const double phi = 0.5 * (1 + std::sqrt(5.0)), s = 1.5 * edge;  // icosahedron edge 3a
    const Vec3 A = s * Vec3{0, 1, phi}, B = s * Vec3{phi, 0, 1}, C = s * Vec3{1, phi, 0};
    const Vec3 P = A + (1.0 / 3) * (B - A), O = (1.0 / 3) * (A + B + C), R = A + (2.0 / 3) * (C - A);
    const Vec3 X = A + (1.0 / 3) * (C - A);  // the long base's midpoint (a T-junction in the shell)
    c.outer_face = {A, P, O, R};
    c.face_distance = norm(O);  // the face ABC is normal to its centre's direction
    // 5-fold contacts are measured from the shell vertex (at 0.25 the two non-adjacent pentamer
    // members' matching sites would come within 0.4, inside the bond range), 3-fold from the
    // face centre; the 2-fold contact is its own partner, so its fractions are symmetric.
    fill_capsomer(c, unit(O), {{A, X, {0.4, 0.85}},     // long base, A half: 5-fold +72 deg
                               {A, P, {0.4, 0.85}},     // short leg: 5-fold -72 deg
                               {O, P, {0.25, 0.75}},    // top: 3-fold +120 deg
                               {O, R, {0.25, 0.75}},    // leg: 3-fold -120 deg
                               {R, X, {0.25, 0.75}}});  // long base, R half: 2-fold
    return c;
}

Capsomer ph_capsomer(double long_edge, SiteDepths depths) {
    if (!(long_edge > 0)) throw std::invalid_argument("ph_capsomer: long_edge must be > 0");
    check_site_depths(depths);
    const std::vector<Quat> group = icosahedral_rotations();
    const double phi = 0.5 * (1 + std::sqrt(5.0));
    const Vec3 five = unit(Vec3{0, 1, phi}), three = unit(Vec3{1, 1, 1});
    // A vertex of the snub dodecahedron: the direction whose orbit under the group has five
    // equal nearest distances. Coarse search between the 5-fold and the 3-fold axis, then
    // coordinate descent to round-off.
    const Vec3 across = unit(cross(five, three));
    Vec3 v = five;
    double best = 1e300;
    for (int i = 1; i < 60; ++i)
        for (int j = 0; j <= 60; ++j) {
            const Vec3 d = (1 - i / 60.0) * five + (i / 60.0) * three + (j / 60.0 - 0.5) * across;
            const double e = edge_spread(group, d);
            if (e < best) best = e, v = d;
        }
    for (double step = 1e-2; step > 1e-14;) {
        bool moved = false;
        for (int k = 0; k < 3; ++k)
            for (const double sign : {1.0, -1.0}) {
                Vec3 d = v;
                d[k] += sign * step;
                const double e = edge_spread(group, d);
                if (e < best) best = e, v = d, moved = true;
            }
        if (!moved) step *= 0.5;
    }
    if (best > 1e-9) throw std::logic_error("ph_capsomer: no snub dodecahedron vertex found");
    // The five faces of the snub around a vertex v, in turn: their poles (reciprocal in the
    // unit sphere) are the corners of the pentagonal hexecontahedron's face dual to v, counter-
    // clockwise seen from outside.
    auto poles_around = [&](const Vec3& v) {
        std::vector<std::pair<double, Vec3>> orbit;
        for (std::size_t g = 1; g < group.size(); ++g) {
            const Vec3 w = rotate(group[g], v);
            orbit.push_back({norm(w - v), w});
        }
        std::sort(orbit.begin(), orbit.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
        const Vec3 e1 = unit(orbit[0].second - dot(orbit[0].second, v) * v), e2 = cross(v, e1);
        std::vector<Vec3> near;
        for (int k = 0; k < 5; ++k) near.push_back(orbit[std::size_t(k)].second);
        std::sort(near.begin(), near.end(), [&](const Vec3& a, const Vec3& b) {
            return std::atan2(dot(a - v, e2), dot(a - v, e1)) < std::atan2(dot(b - v, e2), dot(b - v, e1));
        });
        std::vector<Vec3> pole;
        for (std::size_t k = 0; k < 5; ++k) {
            Vec3 m = unit(cross(near[k] - v, near[(k + 1) % 5] - v));
            if (dot(m, v) < 0) m = -1.0 * m;
            pole.push_back((1 / dot(m, v)) * m);
        }
        return pole;
    };
    // Turn the face so that its 5-fold corner lies on (0, 1, phi) and its 3-fold corner on
    // (1, 1, 1), the shell frame of icosahedral_rotations(); V0 the 5-fold corner, V3 the
    // 3-fold one. The shell's handedness is a choice: the note's enantiomer has the 3-fold
    // corner three steps counter-clockwise from the 5-fold one. The search above finds either
    // enantiomer (their vertices are equally good minima, so which one depends on rounding);
    // the one it did not find is its mirror image.
    auto along = [](const Vec3& x, const Vec3& axis) { return norm(cross(unit(x), axis)) < 1e-9 && dot(x, axis) > 0; };
    Capsomer c;
    Vec3 normal{0, 0, 0};
    v = unit(v);
    for (const Vec3& candidate : {v, Vec3{-v.x, v.y, v.z}}) {
        const std::vector<Vec3> pole = poles_around(candidate);
        for (const Quat& g : group) {
            std::vector<Vec3> f;
            for (const Vec3& p : pole) f.push_back(rotate(g, p));
            int k5 = -1, k3 = -1;
            for (int k = 0; k < 5; ++k) {
                if (along(f[std::size_t(k)], five)) k5 = k;
                if (along(f[std::size_t(k)], three)) k3 = k;
            }
            if (k5 < 0 || k3 < 0 || (k3 - k5 + 5) % 5 != 3) continue;
            std::rotate(f.begin(), f.begin() + k5, f.end());
            const double scale = long_edge / norm(f[1] - f[0]);
            for (Vec3& x : f) x *= scale;
            c.outer_face = f;
            normal = rotate(g, candidate);  // the face lies in the plane x . v = 1 before scaling
            c.face_distance = scale;
            break;
        }
        if (!c.outer_face.empty()) break;
    }
    if (c.outer_face.size() != 5) throw std::logic_error("ph_capsomer: the face does not reach the shell frame");
    c.edge = long_edge;
    c.site_depths = depths;
    const std::vector<Vec3>& V = c.outer_face;
    // Both long edges meet at the 5-fold corner (5-fold contacts, measured from it as in PW);
    // the two edges at the 3-fold corner are the 3-fold contacts, measured from it; V1 V2 is
    // the 2-fold contact, its own partner.
    fill_capsomer(c, normal, {{V[0], V[1], {0.4, 0.85}},
                              {V[0], V[4], {0.4, 0.85}},
                              {V[3], V[2], {0.25, 0.75}},
                              {V[3], V[4], {0.25, 0.75}},
                              {V[1], V[2], {0.25, 0.75}}});
    return c;
}

}  // namespace emergent
